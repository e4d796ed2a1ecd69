// The ground under a LiDAR: the plane the vehicle stands on, seen in the sensor frame. On
// flat ground its normal is the vehicle's z axis and its distance the sensor's height, so
// one revolution gives the mounting's roll, pitch and height, the three components that
// driving on a plane cannot (height) or can only through the tracker's vertical motion
// (roll, pitch) show to the hand-eye solve (hand_eye.hpp).
//
// A RANSAC plane among the returns below the sensor (by the guessed mounting), its normal
// within max_tilt_deg of the guessed up direction, refined by least squares on its inliers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <Eigen/Core>

namespace flat2d::localization::calibration {

struct GroundPlaneOptions {
  double min_range_m = 2.0;   // the vehicle's own body and the mount stay out
  double max_range_m = 25.0;  // far rings are sparse and the ground may bend
  double inlier_distance_m = 0.05;
  int ransac_iterations = 200;
  double max_tilt_deg = 20.0;  // from the guessed up direction
  int min_inliers = 200;
  std::uint32_t seed = 1;
};

struct GroundPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, towards the sensor (up)
  double height_m = 0.0;                              // of the sensor above the plane
  int inliers = 0;
};

// `up` is the vehicle's z axis in the sensor frame by the guessed mounting and
// `guessed_height_m` the guessed height; candidates lie more than half of it below the
// sensor. None when no plane gathers min_inliers.
std::optional<GroundPlane> FitGroundPlane(std::span<const Eigen::Vector3f> points, const Eigen::Vector3d& up, double guessed_height_m,
                                          const GroundPlaneOptions& options = {});

// The mounting's roll and pitch (radians) that turn the vehicle's z axis into `normal` in
// the sensor frame: normal = R^T z with R = Rz(yaw) Ry(pitch) Rx(roll), for any yaw.
Eigen::Vector2d RollPitchOf(const Eigen::Vector3d& normal);

}  // namespace flat2d::localization::calibration
