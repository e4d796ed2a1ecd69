// Keeping chained poses rigid. A product of rotations drifts off SO(3) by rounding, and
// once a pose is not orthonormal, Isometry3d::inverse() (a transpose) is no longer its
// inverse: a loop that takes a motion as previous.inverse() * next and composes it again
// doubles the error every step. Tracking loops renormalize each pose they keep.
#pragma once

#include <Eigen/Geometry>

namespace flat2d::localization::registration {

// `pose` with its rotation replaced by the nearest rotation (through its quaternion).
inline Eigen::Isometry3d Orthonormalized(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d rigid = Eigen::Isometry3d::Identity();
  rigid.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
  rigid.translation() = pose.translation();
  return rigid;
}

}  // namespace flat2d::localization::registration
