// The offline 2D SLAM behind `flat2d-map build` (thesis ch. 3 and 7.3): keyframes of 2D
// structure points with odometry, tied into a pose graph by scan matching, optimized with
// robust loop closures. The same front and back end serve a Velodyne drive (each
// revolution's structure grid, drive_map_build.hpp) and a 2D laser log (carmen_map_build.hpp).
//
// Steps of AddScan: (1) keep the scan as a keyframe once odometry has moved
// keyframe_distance_m or keyframe_angle_rad since the last one; (2) predict its pose from
// the last keyframe's estimate and the odometry between them, and add an odometry factor
// with the odometry model's information; (3) match it against a local map of the previous
// local_map_keyframes keyframes around the prediction (tracking window) and, when the match
// is accepted, add a between factor with the match's covariance and take its pose as the
// estimate (local maps keep only cells that map_min_votes keyframes saw, so traffic in the
// previous keyframes is not matched); the running estimate fuses match and odometry
// (fuse_tracking); (4) look for loop closures: the nearest earlier keyframes whose path
// distance is at least loop_min_path_m, within loop_radius_m plus three standard deviations
// of the drift the chain of steps between them allows, each verified by matching against a
// submap of that keyframe and its neighbours in a window as wide as that drift, and gated:
// a match that disagrees with the graph beyond loop_gate_chi2 is refused. Accepted matches
// become max-mixture factors against a null hypothesis (Olson & Agarwal 2012), so a false
// loop the rest of the graph disagrees with switches itself off. A loop that closes a drift
// of metres would lose to its null hypothesis before the graph could move, so it is solved
// once as a plain Gaussian first (OptimizeGraph); (5) optimize the whole graph
// (Levenberg-Marquardt) once optimize_every new loop closures have been added, at once for
// a drift-closing loop, and in Finish. Between keyframes, poses follow odometry (CorrectedPose).
//
// Refinement: a keyframe tracked against the keyframes before it sees the far side of
// poles, trees and door frames that they saw from the near side, which biases the match
// backwards a little every step (the map shrinks along the path, and turns where the scene
// is lopsided). Finish therefore matches every keyframe again against the keyframes on both
// sides of it at their optimized poses, replaces its tracking factor, and optimizes again,
// refine_sweeps times.
//
// Odometry scale: a wheel-radius error of a few tenths of a percent is invisible to loop
// closures (a uniformly scaled map is self-consistent) and to matches in corridors (which
// do not constrain motion along them), so it would scale the whole map. The builder
// estimates it from the tracking matches that pin the step down along the direction of
// travel (standard deviation there at most scale_max_sigma_m: a wall across the path, not a
// corridor, where the match returns the prediction): the least-squares ratio of matched to
// odometry distance scales the odometry of the following keyframes, and Finish rescales
// every odometry factor with the final estimate before the last optimization. The
// estimate inherits the matches' bias: a local map built from the estimates is
// self-consistent at any uniform scale, so refinement cannot correct it. A known wheel
// calibration can be given instead (odometry_scale, estimate_odometry_scale off).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "localization/graph/pose_graph.hpp"
#include "localization/mapping/odometry_noise.hpp"
#include "localization/mapping/odometry_scale.hpp"
#include "localization/matching/correlative_matcher.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::mapping {

struct MapBuilderOptions {
  double keyframe_distance_m = 0.5;
  double keyframe_angle_rad = 0.25;
  double match_resolution_m = 0.05;
  double point_range_m = 25.0;     // points farther from the sensor are not matched
  double decimation_m = 0.05;      // one point per square this size
  int local_map_keyframes = 40;
  // A map cell is structure once this many keyframes saw it: a car driving by is in a
  // different place in each and drops out, a wall stays.
  std::size_t map_min_votes = 2;
  SearchWindow tracking_window{0.3, 0.1};
  double tracking_min_score = 0.45;
  double loop_radius_m = 4.0;
  double loop_min_path_m = 8.0;
  int loop_candidates = 2;         // nearest candidates tried per keyframe
  int loop_submap_keyframes = 5;   // neighbours on each side in a loop's submap
  SearchWindow loop_window{2.0, 0.4};
  // Far from the last loop the estimate may have drifted metres: candidates are looked for
  // within loop_radius_m plus three standard deviations of the graph's uncertainty between
  // the two keyframes, and matched in a window of three standard deviations, up to these.
  double loop_max_radius_m = 10.0;
  SearchWindow loop_max_window{6.0, 0.4};
  // A match is a loop closure only if it agrees with the graph: the chi-square of its
  // difference from the estimate, over the match's and the graph's covariance, below this
  // (3 degrees of freedom, 99 %).
  double loop_gate_chi2 = 11.34;
  double loop_min_score = 0.55;
  double loop_null_weight = 1e-3;  // max-mixture: weight of the null hypothesis ...
  double loop_null_scale = 1e-6;   // ... and its information relative to the match
  double match_sigma_floor_m = 0.01;
  double match_sigma_floor_rad = 0.002;
  // The running estimate of a new keyframe (the next prediction, the local maps, where
  // loops are looked for) weighs its tracking match against the odometry by their
  // information (the one-node MAP) instead of taking the match, with the match's heading
  // trusted to no better than fuse_heading_floor_rad: along roads lined with trees and
  // posts, matches turn the estimate by a few hundredths of a degree a keyframe, one way,
  // which a gyro does not. The graph's factors are unchanged; only the estimate is.
  bool fuse_tracking = true;
  double fuse_heading_floor_rad = 0.05;
  int optimize_every = 5;          // loop closures between optimizations
  // Refinement in Finish: each keyframe matched again against the refine_keyframes before
  // and after it, so structure seen from both sides is in its map (see the header).
  int refine_sweeps = 2;
  int refine_keyframes = 20;
  SearchWindow refine_window{0.15, 0.03};
  bool estimate_odometry_scale = true;
  // The odometry's scale before any estimate (a wheel calibration): the scale used
  // throughout when estimate_odometry_scale is off, and the fallback when too few steps
  // pin it down.
  double odometry_scale = 1.0;
  double max_scale_error = 0.05;   // the estimate is kept within 1 +- this
  double scale_max_sigma_m = 0.03;  // steps whose match is less sure along the path are not used
  OdometryNoiseModel odometry;     // the odometry factors' uncertainty model
};

struct Keyframe {
  double time_s = 0.0;
  Se2 odometry;  // odom_T_vehicle
  Se2 estimate;  // world_T_vehicle
  std::vector<Eigen::Vector2d> points;  // vehicle frame, range-limited and decimated
  double path_m = 0.0;                  // odometry distance from the first keyframe
};

struct MapBuilderStats {
  std::uint64_t scans = 0;
  std::uint64_t keyframes = 0;
  std::uint64_t tracking_accepted = 0;
  std::uint64_t tracking_rejected = 0;
  std::uint64_t loop_candidates = 0;
  std::uint64_t loop_accepted = 0;   // matched: became max-mixture factors
  std::uint64_t loop_gated = 0;      // matched, but disagreeing with the graph (loop_gate_chi2)
  std::uint64_t loop_drift_closed = 0;  // accepted with an error the match alone would reject (see OptimizeGraph)
  std::uint64_t loop_switched_off = 0;  // ... whose null hypothesis won at the solution (Finish)
  std::uint64_t refined = 0;  // keyframes whose tracking factor the last refinement sweep replaced
  std::uint64_t optimizations = 0;
  double odometry_scale = 1.0;     // the estimate (1 when not estimated)
  double optimize_seconds = 0.0;
  double match_seconds = 0.0;
};

class MapBuilder {
 public:
  explicit MapBuilder(const MapBuilderOptions& options);

  // The world pose of the first keyframe (default: its odometry pose).
  void SetAnchor(const Se2& world_T_first) { anchor_ = world_T_first; has_anchor_ = true; }
  // Offers a scan (points in the vehicle frame) with its odometry pose; true if it became a keyframe.
  bool AddScan(double time_s, const Se2& odometry, std::span<const Eigen::Vector2d> points);
  // The final optimization and loop statistics.
  void Finish();
  // Moves the whole estimate by world_T_map, e.g. the rigid motion that best fits the
  // keyframes to a georeferenced track (GNSS).
  void TransformEstimate(const Se2& world_T_map);
  // Scales the optimized keyframe positions about `centre` (headings unchanged): a scale
  // fixed from outside, e.g. by a GNSS track over the drive.
  void ScaleEstimate(double scale, const Eigen::Vector2d& centre);

  // world_T_vehicle for a vehicle at odometry pose `odometry` at `time_s`: the odometry
  // corrected by the keyframes' estimates around that time (interpolated between them).
  Se2 CorrectedPose(double time_s, const Se2& odometry) const;

  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  const graph::PoseGraph& graph() const { return graph_; }
  const MapBuilderStats& stats() const { return stats_; }
  const MapBuilderOptions& options() const { return options_; }

 private:
  std::vector<Eigen::Vector2d> PrepareScan(std::span<const Eigen::Vector2d> points);
  // Matches keyframe k against the keyframes [first, last] around `prediction`.
  MatchResult MatchAgainst(std::size_t k, std::size_t first, std::size_t last, const Se2& prediction,
                           const SearchWindow& window);
  void MarkVotedStructure(const std::vector<Eigen::Vector2d>& world, const std::vector<std::uint32_t>& source,
                          std::size_t min_votes, MatchGrid& map) const;
  Eigen::Matrix3d MatchInformation(const MatchResult& match) const;
  void TrackNewest();
  struct LoopCandidate {
    double distance_m = 0.0;
    std::size_t keyframe = 0;
    Eigen::Matrix3d chain_covariance;  // the newest keyframe relative to this one, in its frame
  };
  // Loop closures (map_builder_loops.cpp). Earlier keyframes the newest may be at,
  // nearest first (see the header).
  std::vector<LoopCandidate> NearbyKeyframes() const;
  void CloseLoops();
  void TryLoop(std::size_t j, const Eigen::Matrix3d& chain_covariance);
  void OptimizeGraph();
  // Odometry scale (map_builder_scale.cpp).
  Se2 ScaledStep(const Se2& step) const;
  void UpdateScale(const Se2& odometry_step, const Se2& matched_step, const Eigen::Matrix3d& information);
  void RescaleOdometryFactors();
  void RefineSweep();

  MapBuilderOptions options_;
  CorrelativeMatcher matcher_;
  ScanPoints scan_;
  std::vector<Keyframe> keyframes_;
  graph::PoseGraph graph_;
  MapBuilderStats stats_;
  Se2 anchor_;
  bool has_anchor_ = false;
  int loops_since_optimization_ = 0;
  std::vector<std::size_t> odometry_factors_;  // indices into graph_.betweens
  std::vector<std::ptrdiff_t> tracking_factor_;  // per keyframe, into graph_.betweens; -1: none
  // Per keyframe, the covariance of the step into it as the running estimate took it
  // (odometry, and the match as fused): what loop search and gating allow for drift.
  std::vector<Eigen::Matrix3d> step_covariance_;
  // Loops (into graph_.mixture_betweens) that close a drift: held as plain Gaussians in the
  // next optimization, so the graph moves into their basin before the mixture judges them.
  std::vector<std::size_t> drift_loops_;
  double scale_ = 1.0;
  OdometryScaleEstimate scale_estimate_;
};

}  // namespace flat2d::localization::mapping
