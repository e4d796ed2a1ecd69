// How far an estimated rigid transform is from the truth, as registration tests report it:
// the translation and the rotation angle of truth^-1 * estimate.
#pragma once

#include <cmath>

#include <Eigen/Geometry>

namespace flat2d::testing {

struct PoseError {
  double translation_m;
  double rotation_deg;
};

inline PoseError PoseErrorOf(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  const Eigen::Isometry3d error = truth.inverse() * estimate;
  return {error.translation().norm(), Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI};
}

}  // namespace flat2d::testing
