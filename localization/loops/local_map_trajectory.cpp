#include "localization/loops/local_map_trajectory.hpp"

#include <Eigen/Eigenvalues>

#include "localization/loops/trajectory_shape.hpp"

namespace flat2d::localization::loops {

namespace {

// The poses of map `other` in map `index`'s frame.
void AppendInFrame(std::vector<Eigen::Isometry3d>& out, const LocalMapTrajectory& frame, const LocalMapTrajectory& other,
                   std::size_t first, std::size_t last) {
  const Eigen::Isometry3d frame_T_other = frame.world_T_map.inverse() * other.world_T_map;
  for (std::size_t k = first; k < last; ++k) out.push_back(frame_T_other * other.map_T_pose[k]);
}

}  // namespace

PathAround PathAroundMap(std::span<const LocalMapTrajectory> maps, int index, double before_m, double after_m) {
  const auto& self = maps[static_cast<std::size_t>(index)];
  const double own_end = self.path_start_m + ArcLengths(self.map_T_pose).back();
  int first = index;
  while (first > 0 && maps[static_cast<std::size_t>(first)].path_start_m > self.path_start_m - before_m) --first;
  int last = index;
  while (last + 1 < static_cast<int>(maps.size()) && maps[static_cast<std::size_t>(last + 1)].path_start_m < own_end + after_m) {
    ++last;
  }
  PathAround path;
  for (int k = first; k <= last; ++k) {
    const auto& map = maps[static_cast<std::size_t>(k)];
    if (k == index) {
      path.first_own = static_cast<int>(path.map_T_pose.size());
      path.own_count = static_cast<int>(map.map_T_pose.size());
    }
    // Consecutive maps share their boundary pose: each map after the first adds its own from the second.
    const std::size_t skip = (k > first && !map.map_T_pose.empty()) ? 1 : 0;
    if (k == index && skip == 1) {
      --path.first_own;
    }
    AppendInFrame(path.map_T_pose, self, map, skip, map.map_T_pose.size());
  }
  path.length_m = ArcLengths(path.map_T_pose).back();
  return path;
}

Eigen::Vector3d TrajectorySpread(std::span<const Eigen::Isometry3d> path) {
  if (path.size() < 2) return Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& pose : path) mean += pose.translation();
  mean /= static_cast<double>(path.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& pose : path) {
    const Eigen::Vector3d d = pose.translation() - mean;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(path.size());
  const Eigen::Vector3d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues();  // ascending
  return eigenvalues.reverse().cwiseMax(0.0).cwiseSqrt();
}

bool IsInformative(std::span<const Eigen::Isometry3d> path, double min_spread_m) {
  return TrajectorySpread(path)(1) >= min_spread_m;
}

}  // namespace flat2d::localization::loops
