// `flat2d-map calibrate DRIVE [DRIVE2]`: where each LiDAR sits on the vehicle, and where
// the two sit relative to each other (thesis 6.2.2).
//
// Ground first: on flat ground the plane under the sensor (calibration/ground_plane.hpp,
// every 10th revolution, medians) gives the mounting's roll, pitch and height. Motion alone
// cannot be trusted with them: where the scene leaves the sensor's vertical motion free
// (the ground cut away beyond 4 m, walls only), NICP keeps the odometry guess's, which
// comes through the guessed mounting, and the solve confirms the guess (on the ramps yard,
// VLP-16, pitch went from 5 deg off to 3.3, 6.8 and 6.9 deg off over three passes).
//
// Sensor to vehicle (Eq. 6.1-6.3): the drive's revolutions tracked by NICP against their
// merged model (nicp_drive_build.hpp, no planar constraint) give the sensor's motions, the
// CAN odometry the vehicle's over the same intervals (about 1 m or 0.1 rad each), and the
// hand-eye solve (calibration/hand_eye.hpp) the mounting. The tracking itself leans on the
// mounting (deskewing by odometry, the guess, the ground cut), so it runs again with the
// estimate: passes = 2 by default. On planar drives the height is unobservable and keeps
// the guess (said in the result).
//
// Sensor to sensor: each drive's reconstruction (its first revolutions, ground included,
// deskewed and placed at their tracked poses in the frame of its sensor at its first
// revolution) registered to the first drive's by NICP in KD-tree mode, coarse (2 m gate)
// then fine, from the two mountings' guess. The drives are one drive recorded by two
// sensors: their first revolutions start together (else drive 1's tracked motion bridges
// the time between them), with the vehicle where it was for both.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "localization/calibration/ground_plane.hpp"
#include "localization/calibration/hand_eye.hpp"
#include "localization/tools/nicp_drive_build.hpp"

namespace flat2d::localization::tools {

struct CalibrationDrive {
  std::filesystem::path capture, can_log, dbc;
  Eigen::Isometry3d initial_vehicle_T_sensor = Eigen::Isometry3d::Identity();  // the guess
};

struct CalibrateOptions {
  std::vector<CalibrationDrive> drives;  // one or two
  std::filesystem::path odometry_config;
  NicpDriveOptions tracking;             // capture, CAN files and mounting are set per drive
  calibration::HandEyeOptions hand_eye;
  double pair_distance_m = 1.0;          // each motion pair: this far ...
  double pair_angle_rad = 0.1;           // ... or this much turned
  int passes = 2;
  // Scale the odometry's distances to the tracked ones before the solve (hand_eye.hpp,
  // OdometryDistanceScale).
  bool scale_odometry = true;
  // Roll, pitch and height from the ground plane, the hand-eye solve left with x, y and yaw
  // (false: all six by motion, Eq. 6.3 alone).
  bool use_ground = true;
  calibration::GroundPlaneOptions ground;
  int ground_every = 10;  // revolutions
  // The reconstructions registered for the sensor pair: each drive's first revolutions
  // (every reconstruction_stride-th point), before the tracker's drift tilts them apart
  // (the tracker's model over the whole 50 s ramps drive left the two VLP-16
  // reconstructions 1 deg apart in roll and pitch), and their unorganized statistics
  // radius, wide enough to span the rings (0.3 m left the pair 8 cm and 0.25 deg off).
  int reconstruction_revolutions = 30;
  int reconstruction_stride = 2;
  // ... and at most this many points (an HDL-32E's 30 revolutions hold 1 M at stride 2,
  // whose statistics and registration took 171 s, against 11 s for the VLP-16's 0.27 M).
  int reconstruction_max_points = 300'000;
  float reconstruction_radius_m = 0.5F;
};

// The medians of the ground plane over the revolutions it was found in.
struct GroundEstimate {
  double roll_deg = 0.0, pitch_deg = 0.0, height_m = 0.0;
  int revolutions = 0;  // with a plane
  int tried = 0;        // looked at
};

struct SensorCalibration {
  calibration::HandEyeResult hand_eye;
  std::optional<GroundEstimate> ground;  // with use_ground
  std::string sensor;  // the capture's model ("vlp16", ...)
  double odometry_scale = 1.0;  // tracked / odometry distance on straight intervals
  int frames = 0, failures = 0;
  double seconds = 0.0;  // every pass's tracking and solve
};

struct SensorPairCalibration {
  Eigen::Isometry3d sensor1_T_sensor2 = Eigen::Isometry3d::Identity();  // registered
  Eigen::Isometry3d from_hand_eye = Eigen::Isometry3d::Identity();      // P1^-1 P2, the guess
  int inliers = 0;
  int iterations = 0;
  double chi2 = 0.0;
  std::size_t points1 = 0, points2 = 0;  // the reconstructions
  double seconds = 0.0;
};

struct CalibrateResult {
  std::vector<SensorCalibration> sensors;     // per drive
  std::optional<SensorPairCalibration> pair;  // with two drives
};

// Errors name the drive's file (capture, CAN log, DBC, odometry configuration), a drive
// without enough motion, or a failed registration of the reconstructions.
Result<CalibrateResult> Calibrate(const CalibrateOptions& options);

}  // namespace flat2d::localization::tools
