// The L2G localizer (thesis 7.2, DESIGN.md "L2G factor graph"): the vehicle's odometry
// frame `local` is tied to the prior map's frame `global` by global_T_local (L2G), estimated
// from each revolution's structure grid matched against the map and fused with odometry in
// a bounded sliding-window factor graph.
//
// Per revolution (AddGrid), with the grid's reference pose local_T_vehicle and time t:
//  1. predict global_T_vehicle = L2G x local_T_vehicle, and move the map window there when
//     the vehicle has left its centre, or to the nearest viewpoint sub-map (map_window.hpp);
//     the next mosaic window is prepared on a worker thread ahead of time (map_prefetch.hpp);
//  2. match the grid's slammable cells (vehicle frame, within point_range_m, decimated)
//     against the window: tracking mode around the prediction, or, when lost, a global
//     relocalization around it whose radius widens after every failure;
//  3. add a node at t, the odometry between it and the previous node (pose_history.hpp H2,
//     with its covariance), and an accepted match as a max-mixture factor against a broad
//     null hypothesis, so one wrong match cannot drag the pose (sliding_window.hpp);
//  4. solve the window (the oldest nodes are marginalized into a prior) and publish
//     L2G = global_T_vehicle(t) x local_T_vehicle(t)^-1 with the newest node's covariance;
//  5. update the state (localizer_state.hpp): LOCALIZED while matches are accepted,
//     DEGRADED after degraded_after without one, LOST after lost_after or when the position
//     is more uncertain than lost_sigma_m. A global match restarts the window from its pose
//     but stays on probation (LOST) until relocalization_confirmations tracking matches in a
//     row accept it; the first rejection resumes the search.
// Between revolutions PoseAt composes the newest node with the odometry since its time, so
// poses come at odometry rate with covariance from both.
//
// Fixed memory: the matcher, the map windows, the scan buffer and the graph are sized in
// Create; AddGrid, PoseAt and SetInitialPose do not allocate, nor does the prefetch worker
// (a test counts).
#pragma once

#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "localization/graph/sliding_window.hpp"
#include "localization/localizer/localization_fix.hpp"
#include "localization/localizer/localizer_options.hpp"
#include "localization/localizer/localizer_state.hpp"
#include "localization/localizer/map_prefetch.hpp"
#include "localization/localizer/map_window.hpp"
#include "localization/matching/correlative_matcher.hpp"
#include "localization/odometry/pose_history.hpp"
#include "localization/odometry/se2.hpp"
#include "maps/grid/revolution_gridder.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::localization {

// What one revolution did.
struct RevolutionReport {
  bool used = false;  // the grid was complete, had odometry, and a fix existed
  LocalizerState state = LocalizerState::kInitializing;
  bool relocalizing = false;     // the match was a global search
  MatchStatus match = MatchStatus::kNoMap;
  double score = 0.0;
  Se2 match_pose;                // global_T_vehicle the match found (when it ran)
  Eigen::Matrix3d match_covariance = Eigen::Matrix3d::Zero();  // ... as the score surface says
  bool match_accepted = false;   // passed the score threshold and was not switched off
  std::size_t points = 0;        // scan points matched
  int headings = 0;              // headings the search tried
  double match_s = 0.0;          // CPU time of the match (including a map window move)
  double solve_s = 0.0;          // ... and of the graph solve
};

struct LocalizerStats {
  std::uint64_t grids = 0;
  std::uint64_t grids_without_odometry = 0;
  std::uint64_t matches_accepted = 0;
  std::uint64_t matches_rejected = 0;  // below the score, failed, or on the null hypothesis
  std::uint64_t relocalizations = 0;   // global searches run
  std::uint64_t relocalized = 0;       // ... that were accepted
  std::uint64_t relocalizations_refuted = 0;  // ... and then not confirmed by tracking
  std::uint64_t map_window_moves = 0;
  std::uint64_t map_errors = 0;        // damaged tiles met while moving the window
  std::uint64_t map_prefetches = 0;        // windows prepared on the worker thread...
  std::uint64_t map_prefetches_taken = 0;  // ... and taken when the move fell due
  std::uint64_t map_prefetch_waits = 0;    // moves that waited for the worker to finish
  double map_prefetch_cpu_s = 0.0;         // the worker's CPU time for them, in all
};

class Localizer {
 public:
  // Takes the map; its reader's cache is set by map_cache_tiles at Open (the caller's).
  static Result<Localizer> Create(maps::PriorMapReader map, const LocalizerOptions& options);

  // The vehicle's global pose at `time_ns` with its uncertainty: from configuration, a
  // persisted L2G, a client or GNSS. Takes effect at the next grid; a covariance wider than
  // the tracking window starts a relocalization within three standard deviations.
  void SetInitialPose(TimeNs time_ns, const Se2& global_T_vehicle, const Eigen::Matrix3d& covariance);

  // One revolution's grid, with the odometry that placed its fans.
  RevolutionReport AddGrid(const maps::PublishedGrid& grid, const PoseHistory& odometry);

  // global_T_vehicle at `time_ns` (odometry rate); not ok before the first fix or outside
  // the odometry's window.
  GlobalPose PoseAt(TimeNs time_ns, const PoseHistory& odometry) const;

  // Advances the state to `time_ns` without a grid (the LiDAR is silent): DEGRADED once
  // degraded_after has passed since the last accepted match, LOST once the pose's uncertainty,
  // grown by the odometry since the last node, exceeds lost_sigma_m. Does nothing without a fix.
  void Tick(TimeNs time_ns, const PoseHistory& odometry);

  LocalizationFix fix() const;

  LocalizerState state() const { return state_; }
  const Se2& global_T_local() const { return global_T_local_; }
  const LocalizerStats& stats() const { return stats_; }
  int graph_nodes() const { return graph_.size(); }
  const maps::PriorMapReader& map() const { return *map_; }

 private:
  Localizer(maps::PriorMapReader map, const LocalizerOptions& options, MapWindow window,
            std::optional<MapWindow> spare_window, graph::SlidingWindowGraph graph);

  void StartFromInitialPose(TimeNs time_ns, const Se2& local_T_vehicle, const PoseHistory& odometry);
  void ExtractScan(const maps::ClassGrid& grid);
  MatchResult MatchScan(const Se2& prediction, TimeNs time_ns, const PoseHistory& odometry, RevolutionReport& report);
  // Moves the window (and the matcher's map) to cover `position`: the prepared window when
  // it fits, else a fill; then starts the next prefetch when it is time. Whether it moved.
  Result<bool> CoverMosaic(const Eigen::Vector2d& position, double max_offset_m);
  // Waits for a running prefetch and drops it: the map reader is the tracking thread's again.
  void DropPrefetch();
  SearchWindow TrackingWindow(TimeNs time_ns, const PoseHistory& odometry) const;
  bool Accepts(const MatchResult& match) const;
  void WidenRelocalization();  // the next global search's window, after a failed or refuted one
  void Track(TimeNs time_ns, const Se2& local_T_vehicle, const Se2& prediction, const MatchResult& match,
             const PoseHistory& odometry, RevolutionReport& report);
  void Restart(TimeNs time_ns, const Se2& global_T_vehicle, const Eigen::Matrix3d& information);
  void UpdateState(TimeNs time_ns, double position_sigma_m);
  // Adds the time since the previous revolution to unmatched_ns_ (0 again on an accepted match).
  void CountUnmatched(TimeNs time_ns, bool accepted);
  // One revolution counts for at most this much unmatched time: a gap in the revolutions
  // (LiDAR silence) is not a stretch of failed matches.
  static constexpr TimeNs kMaxRevolutionStep = 250 * kNsPerMs;
  Eigen::Matrix3d MatchInformation(const Eigen::Matrix3d& covariance) const;
  Eigen::Matrix3d OdometryInformation(const RelativeMotion& motion) const;

  LocalizerOptions options_;
  // On the heap: the prefetch worker holds its address while the Localizer may move.
  std::unique_ptr<maps::PriorMapReader> map_;
  MapWindow window_;
  CorrelativeMatcher matcher_;
  std::unique_ptr<MapPrefetch> prefetch_;  // after map_ and the matcher: stopped before them
  ScanPoints scan_;
  graph::SlidingWindowGraph graph_;
  LocalizerStats stats_;

  LocalizerState state_ = LocalizerState::kInitializing;
  bool has_initial_pose_ = false;  // set, not yet applied
  TimeNs initial_time_ns_ = 0;
  Se2 initial_pose_;
  Eigen::Matrix3d initial_covariance_ = Eigen::Matrix3d::Identity();

  bool has_fix_ = false;  // the graph holds a node
  Se2 global_T_local_;
  TimeNs last_node_ns_ = 0;
  Se2 last_node_pose_;                                    // global_T_vehicle, solved
  Eigen::Matrix3d last_node_covariance_ = Eigen::Matrix3d::Zero();
  TimeNs last_accepted_ns_ = 0;
  TimeNs last_grid_ns_ = 0;   // the newest revolution matched (0: none since the initial pose)
  TimeNs unmatched_ns_ = 0;   // revolution time since the last accepted match, gaps excluded
  bool ever_localized_ = false;  // a match was accepted since the last initial pose
  bool relocalizing_ = false;
  int confirmations_needed_ = 0;  // tracking matches still to accept after a global match
  // The next global search: its radius, and its headings, an initial pose's 3 sigma (a warm
  // start knows its heading to 0.2 rad, so it need not try all), pi once lost while tracking.
  SearchWindow relocalization_window_{0.0, std::numbers::pi};
};

}  // namespace flat2d::localization
