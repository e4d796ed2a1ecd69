// The sensor's pose on the vehicle from motion (thesis 6.2.2, Eq. 6.1-6.3): the sensor's
// own motions C_ij (tracked LiDAR) against the vehicle's T_ij (odometry) over the same
// intervals, P* = argmin_P sum || C_ij^-1 P^-1 T_ij P ||, incremental motions so that
// neither track's drift enters.
//
// P is solved for in the mounting's six numbers (x, y, z, roll, pitch, yaw: Z-Y-X Euler),
// by Gauss-Newton with a Huber kernel on each whitened 6D error. Components the motions do
// not constrain are left where the initial guess put them and reported: on a planar drive
// every vehicle rotation turns about the vehicle's z, (R_T - I) t_P has no z component, and
// the sensor's height cannot be told from any amount of driving.
#pragma once

#include <array>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"

namespace flat2d::localization::calibration {

// One interval: the sensor's motion (sensor_i_T_sensor_j) and the vehicle's over it.
struct MotionPair {
  Eigen::Isometry3d sensor_motion = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d vehicle_motion = Eigen::Isometry3d::Identity();
};

struct HandEyeOptions {
  // The error's standard deviations: the tracked and odometry motions over one interval
  // (about 1 m) disagree by centimetres and tenths of a degree.
  double sigma_translation_m = 0.02;
  double sigma_rotation_rad = 0.0035;
  double huber_threshold = 3.0;  // on the whitened error's norm; beyond it after the first stage: left out
  int max_iterations = 30;  // per stage (Huber, then inliers only)
  double convergence_step = 1e-6;  // stop when the step, in standard deviations, is smaller
  // A direction of the (Jacobi-scaled) information is unconstrained when its eigenvalue is
  // under this share of the largest; a component is unobservable when such directions hold
  // more than half of it.
  double null_eigenvalue_share = 1e-6;
  int min_pairs = 10;
  // A component whose 1-sigma comes out above these is held at the guess and reported
  // unobservable: the drive does not determine it well enough to replace a measured guess.
  double max_sigma_m = 0.05;
  double max_sigma_deg = 0.5;
  // Components known otherwise (the ground plane's roll, pitch and height) stay at the
  // initial value and are reported unobservable.
  std::array<bool, 6> fixed{};
};

// The mounting's components in the order the solver uses.
inline constexpr std::array<std::string_view, 6> kMountingComponents{"x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg"};

struct HandEyeResult {
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();
  std::array<bool, 6> observable{};   // per kMountingComponents
  std::array<double, 6> sigma{};      // 1-sigma of each observable component (m, deg); 0 if not
  int pairs = 0;
  int inliers = 0;                    // pairs inside the Huber threshold at the end
  int iterations = 0;
  double rms_translation_m = 0.0;     // of the final errors, inliers only
  double rms_rotation_deg = 0.0;
};

// An error when there are fewer than options.min_pairs pairs, a pose is not finite, or the
// motions constrain nothing.
Result<HandEyeResult> SolveHandEye(std::span<const MotionPair> pairs, const Eigen::Isometry3d& initial_vehicle_T_sensor,
                                   const HandEyeOptions& options = {});

// The odometry's distance scale against the sensor's: the median ratio of the sensor's to
// the vehicle's distance over the pairs that turn less than max_angle_rad, where the lever
// arm leaves the distance alone (none: 1). A wheel odometry a fraction s long would
// otherwise pass for a lateral lever arm of s times the turn radius: 0.5 % on the campus's
// 40 m curves is 20 cm.
double OdometryDistanceScale(std::span<const MotionPair> pairs, double max_angle_rad = 0.005);

// The intervals of two trajectories sampled at the same instants (sensor poses in any fixed
// frame, vehicle poses in any fixed frame): from each pose i to the first j after it with
// the vehicle min_distance_m or min_angle_rad from it.
std::vector<MotionPair> MotionPairs(std::span<const Eigen::Isometry3d> world_T_sensor,
                                    std::span<const Eigen::Isometry3d> odometry_T_vehicle, double min_distance_m = 1.0,
                                    double min_angle_rad = 0.1);

}  // namespace flat2d::localization::calibration
