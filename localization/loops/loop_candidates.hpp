// Loop-closure candidates for the newest local map (thesis 6.3.2), before any point is
// registered:
//  (a) by distance: past maps whose centre lies within a radius of the newest map's centre,
//      in the graph's current estimate; the guess is the estimate itself. Blind once the
//      drift exceeds the radius.
//  (b) by trajectory shape: past informative maps whose path, with its neighbours', the
//      newest map's path fits (Eq. 6.13, trajectory_shape.hpp), from several random
//      associations each; the guess is T*. Independent of the estimate's drift.
// Maps nearer than min_path_separation_m along the drive are neighbours, not loops.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "localization/loops/local_map_trajectory.hpp"
#include "localization/loops/trajectory_shape.hpp"

namespace flat2d::localization::loops {

struct LoopCandidateOptions {
  double min_path_separation_m = 50.0;
  double distance_radius_m = 10.0;  // (a)

  // (b)
  double min_spread_m = 0.05;       // both maps informative: second spread at least this
  // Path either side of each map that the fit may use. 15 m: in the simulated office the
  // revisits come in from other corridors and 30 m found neither informative revisit, 15 m
  // both; on KITTI 00 (seed 1) 15 m and 30 m find the same 6 of 12.
  double context_m = 15.0;
  // Maps whose internal rotations (first to last pose) differ more than this are not tried.
  double max_turn_difference_rad = 0.35;
  // Associations tried per past map, each of one of its poses with the newest map's middle
  // pose: from a random first one, a pose every association_spacing_m along the map, so
  // that with the offset search of trajectory_shape.hpp (step 5) every alignment is covered.
  double association_spacing_m = 1.5;
  std::uint32_t random_seed = 1;
  double max_rms_translation_m = 0.3;
  double max_rms_rotation_rad = 0.05;
  // The fit must follow the past path this far: the newest map's own length and some of
  // the path before it (revisits often come in from another street).
  double min_matched_m = 10.0;
  // When above 0, T* must also put the newest map within max(drift_min_radius_m,
  // drift_fraction x path driven since the past map) of its estimate: a drift bound.
  double drift_fraction = 0.0;
  double drift_min_radius_m = 10.0;
  ShapeAlignmentOptions alignment;
};

enum class CandidateSource { kDistance, kTrajectoryShape };

struct LoopCandidate {
  int reference = 0;  // the past map
  int current = 0;    // the newest map
  CandidateSource source = CandidateSource::kDistance;
  Eigen::Isometry3d reference_T_current = Eigen::Isometry3d::Identity();  // the registration's guess
  double rms_translation_m = 0.0;   // (b): Eq. 6.13's fit
  double matched_length_m = 0.0;    // (b)
};

// (a) for maps[current] against maps[0..current).
std::vector<LoopCandidate> DistanceCandidates(std::span<const LocalMapTrajectory> maps, int current,
                                              const LoopCandidateOptions& options);

// (b) likewise. Deterministic for a given options.random_seed.
std::vector<LoopCandidate> TrajectoryShapeCandidates(std::span<const LocalMapTrajectory> maps, int current,
                                                     const LoopCandidateOptions& options);

// Whether the chain between maps `a` and `b` (either order) holds a tie whose registration
// failed: tie i joins maps i and i + 1, tie_failed[i] marks it. Across such a tie a
// candidate's guess is the odometry's, which can be metres off, not the tracking's.
bool ChainCrossesFailure(const std::vector<bool>& tie_failed, int a, int b);

}  // namespace flat2d::localization::loops
