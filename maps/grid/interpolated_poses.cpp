#include "maps/grid/interpolated_poses.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flat2d::maps {

StampedPose2d Flatten(TimeNs time_ns, const Eigen::Isometry3d& world_T_body) {
  const Eigen::Vector3d x_axis = world_T_body.linear().col(0);
  return {time_ns, world_T_body.translation().head<2>(), std::atan2(x_axis.y(), x_axis.x())};
}

Eigen::Isometry3d Lift(const Eigen::Isometry2d& pose) {
  Eigen::Isometry3d lifted = Eigen::Isometry3d::Identity();
  lifted.linear().topLeftCorner<2, 2>() = pose.linear();
  lifted.translation().head<2>() = pose.translation();
  return lifted;
}

InterpolatedPoses::InterpolatedPoses(std::vector<StampedPose2d> poses) : poses_(std::move(poses)) {}

std::optional<Eigen::Isometry2d> InterpolatedPoses::PoseAt(TimeNs t) const {
  if (poses_.empty() || t < poses_.front().time_ns || t > poses_.back().time_ns) return std::nullopt;
  const auto after = std::lower_bound(poses_.begin(), poses_.end(), t,
                                      [](const StampedPose2d& p, TimeNs time) { return p.time_ns < time; });
  if (after->time_ns == t || after == poses_.begin()) {
    return Eigen::Translation2d(after->position) * Eigen::Rotation2Dd(after->yaw);
  }
  const StampedPose2d& a = *(after - 1);
  const StampedPose2d& b = *after;
  const double s = static_cast<double>(t - a.time_ns) / static_cast<double>(b.time_ns - a.time_ns);
  const double turn = std::remainder(b.yaw - a.yaw, 2.0 * std::numbers::pi);  // shorter arc
  return Eigen::Translation2d(a.position + s * (b.position - a.position)) * Eigen::Rotation2Dd(a.yaw + s * turn);
}

}  // namespace flat2d::maps
