// What the simulated Velodyne is: model, return mode, rotation, mounting, the measurement
// errors and the clocks, with defaults taken from the manuals where they say something
// (VLP-16 63-9243 Rev E, HDL-32E 63-9113 Rev M, VLP-32C 63-9325 Rev C, "Specifications")
// and from the shared real captures where they do not (position-packet rates, NMEA
// formats). Start from DefaultLidarOptions(model) and change what the run needs;
// ValidateLidarOptions says which field is wrong.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::sim {

// 2026-01-01T00:00:00Z: drive time 0 of every run, so timestamps are reproducible.
inline constexpr TimeNs kDefaultStartEpochNs = 1'767'225'600 * kNsPerSecond;

// Where the world frame (x east, y north) sits on the WGS-84 ellipsoid.
struct GeoOrigin {
  double latitude_deg = 47.9990;   // Freiburg im Breisgau; any place works
  double longitude_deg = 7.8421;
};

// Optional GNSS receiver attached to the sensor: one $GPRMC fix per second (PPS second S),
// which the position packets repeat from S + sentence_latency_s until the next one arrives.
struct GnssOptions {
  bool enabled = false;            // off: no receiver, position packets without a sentence
  GeoOrigin origin;
  double horizontal_sigma_m = 1.0; // per-axis Gaussian error of each fix (east, north)
  // A survey (RTK) receiver, as mapping vehicles carry: fixes to rtk_sigma_m and written
  // with seven decimals of minutes (1.85 mm), not the HDL-32E Garmin's four (18.5 cm).
  bool rtk = false;
  double rtk_sigma_m = 0.02;
  // The MRPT VLP-16 capture's packets run 0.34-0.73 s ahead of their fix: the sentence
  // arrives about 0.35 s after its PPS second.
  double sentence_latency_s = 0.35;
};

struct LidarOptions {
  velodyne::Model model = velodyne::Model::kHdl32e;
  velodyne::ReturnMode return_mode = velodyne::ReturnMode::kStrongest;
  // Calibration the simulated sensor has (and a decoder must be given); none: the
  // manual's factory table (DefaultLaserTable).
  std::optional<velodyne::LaserTable> laser_table;
  double rotation_hz = 10.0;        // 5-20 Hz (300-1200 rpm)
  double start_azimuth_deg = 0.0;   // azimuth of the first firing at drive time 0
  // The sensor frame (x forward, y left, z up) in the vehicle frame (trajectory.hpp).
  Eigen::Isometry3d vehicle_T_sensor{Eigen::Translation3d(0.0, 0.0, 1.9)};

  double range_noise_sigma_m = 0.01;  // Gaussian, along the ray
  double dropout_probability = 0.0;   // a return that is lost (no return recorded)
  double min_range_m = 0.9;           // closer hits are not reported
  double max_range_m = 100.0;         // farther hits are not reported

  // Clocks: Unix time = start_epoch_ns + drive time. The device clock is UTC (as if
  // PPS-disciplined); a host receives a data packet capture_latency_us after its last
  // firing and a position packet capture_latency_us after the sensor assembled it.
  TimeNs start_epoch_ns = kDefaultStartEpochNs;
  double start_drive_time_s = 0.0;  // the first packets are those at or after this time
  double capture_latency_us = 100.0;

  bool position_packets = true;
  double position_period_us = 6859.0;  // VLP-16 capture: 146/s; HDL-32E capture: 205/s
  GnssOptions gnss;
};

// Defaults for a model. Range accuracy (manuals): VLP-16 and VLP-32C +-3 cm typical,
// HDL-32E +-2 cm; read as about 2 sigma, so sigma = 1.5 cm and 1.0 cm. Maximum range:
// 100 m (VLP-16, HDL-32E: "80 m to 100 m"), 200 m (VLP-32C). Minimum range 0.9 m: the
// manuals give none; it is the velodyne_pointcloud driver's default cut.
LidarOptions DefaultLidarOptions(velodyne::Model model);

// The laser table the options describe (laser_table or the model's factory table).
velodyne::LaserTable LaserTableOf(const LidarOptions& options);

// Names the first invalid field, e.g. "lidar options: rotation_hz 25 outside [5, 20]".
Status ValidateLidarOptions(const LidarOptions& options);

}  // namespace flat2d::hal::sim
