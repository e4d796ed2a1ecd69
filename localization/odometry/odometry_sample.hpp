// One dead-reckoned pose: what DeadReckoning produces per step and PoseHistory stores.
//
// Besides the pose and its covariance it keeps the covariance of the step that led to it
// (the motion since the previous sample). Dead-reckoned poses are correlated along the
// chain, so the covariance of the motion between two times is the sum of the steps in
// between (propagated with se2.hpp E5), not a difference of the two absolute covariances:
// those grow without bound over a long drive while the steps stay small.
#pragma once

#include <Eigen/Core>

#include "hal/common/time.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

struct OdometrySample {
  TimeNs time_ns = 0;
  Se2 local_T_vehicle;
  // Of (x, y, theta) of local_T_vehicle, x and y along the local axes (se2.hpp).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // Of (x, y, theta) of previous_T_vehicle, the step from the previous sample, x and y along
  // the previous vehicle axes. Zero for the first sample and for steps without motion.
  Eigen::Matrix3d step_covariance = Eigen::Matrix3d::Zero();
  // The step from the previous sample was not measured: a gap longer than the configured
  // maximum (pose held or extrapolated), or no usable speed or yaw rate. Relative motion
  // across it is an assumption, and PoseHistory says so.
  bool discontinuity = false;
};

}  // namespace flat2d::localization
