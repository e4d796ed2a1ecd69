// What the loop closer knows of a local map without its points (thesis 6.3, Fig. 6.6): the
// map's pose in the graph's current estimate, the internal trajectory it was built along,
// and where along the drive it started. The points stay on disk; this stays in memory.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Geometry>

namespace flat2d::localization::loops {

struct LocalMapTrajectory {
  Eigen::Isometry3d world_T_map = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> map_T_pose;  // the internal trajectory, in driving order
  double path_start_m = 0.0;                  // distance driven when the map began
};

// A stretch of the drive in one map's frame: the map's own poses and its neighbours' up to
// `before_m` / `after_m` of path either side, placed by the graph's estimates of the maps
// (consecutive maps' relative poses are tracked, so locally sound). `first_own` and
// `own_count` locate the map's own poses in `map_T_pose`.
struct PathAround {
  std::vector<Eigen::Isometry3d> map_T_pose;
  int first_own = 0;
  int own_count = 0;
  double length_m = 0.0;
};
PathAround PathAroundMap(std::span<const LocalMapTrajectory> maps, int index, double before_m, double after_m);

// The spread of a trajectory's positions: the square roots of its covariance's eigenvalues,
// largest first (m). A straight path has one clearly above zero, a turn two.
Eigen::Vector3d TrajectorySpread(std::span<const Eigen::Isometry3d> path);

// Thesis 6.3.2: informative when at least two spreads are clearly above zero.
bool IsInformative(std::span<const Eigen::Isometry3d> path, double min_spread_m);

}  // namespace flat2d::localization::loops
