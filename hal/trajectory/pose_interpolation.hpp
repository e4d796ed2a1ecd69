// A pose between two poses: the position linearly, the rotation by slerp (Eigen's takes the
// shorter arc, so q and -q interpolate alike). Shared by the trajectory evaluation, the
// calibration's sensor track and the loop closer's paths.
#pragma once

#include <Eigen/Geometry>

namespace flat2d::hal::trajectory {

// fraction 0 gives a, 1 gives b.
inline Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double fraction) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Quaterniond(a.linear()).slerp(fraction, Eigen::Quaterniond(b.linear())).normalized().toRotationMatrix();
  pose.translation() = (1.0 - fraction) * a.translation() + fraction * b.translation();
  return pose;
}

}  // namespace flat2d::hal::trajectory
