// Corrupting a reference trajectory into odometry (issue 8's protocol for the public 2D
// logs, whose raw odometry is not available): the reference's motion between consecutive
// poses, in the body frame, gets seeded Gaussian errors that grow with the motion, and the
// noisy motions are chained from the first reference pose. The result drifts like wheel
// odometry (a random walk in position and heading), reproducibly for a seed.
//
// Per step, with d the distance and dtheta the heading change of the reference motion:
//   forward  d (1 + s) + N(0, (translation_fraction d)^2),     s ~ N(0, scale_sigma^2) once
//   lateral  lateral + N(0, (lateral_fraction d)^2)
//   heading  dtheta + N(0, (rotation_fraction |dtheta| + rotation_per_metre d)^2)
// s is one scale error for the whole drive (a mis-calibrated wheel radius).
#pragma once

#include <cstdint>
#include <vector>

#include "localization/odometry/se2.hpp"

namespace flat2d::localization::mapping {

struct OdometryNoiseModel {
  double translation_fraction = 0.05;   // 5 % of the distance, 1 sigma
  double lateral_fraction = 0.02;
  double rotation_fraction = 0.05;      // 5 % of the turn
  double rotation_per_metre = 0.01;     // rad per metre driven (0.57 deg/m)
  double scale_sigma = 0.01;            // 1 % wheel-radius error
  std::uint64_t seed = 1;
};

// The noisy odometry poses, one per reference pose, starting at reference.front().
std::vector<Se2> CorruptOdometry(const std::vector<Se2>& reference, const OdometryNoiseModel& model);

// The information matrix the model implies for one step of odometry `step` (body frame
// x, y, theta), with floors so a standstill is not infinitely certain.
Eigen::Matrix3d OdometryInformation(const Se2& step, const OdometryNoiseModel& model);

}  // namespace flat2d::localization::mapping
