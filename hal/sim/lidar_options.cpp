#include "hal/sim/lidar_options.hpp"

#include <cmath>
#include <string>

namespace flat2d::hal::sim {
namespace {

using velodyne::Model;

// Largest range a data packet can carry: 65535 distance units (packet_encoder.hpp).
double LargestEncodableRange(const velodyne::LaserTable& table) {
  return 65535.0 * table.distance_resolution_m;
}

Error FieldError(const std::string& field, double value, const std::string& why) {
  return MakeError("lidar options: " + field + " " + std::to_string(value) + " " + why);
}

bool IsFiniteIsometry(const Eigen::Isometry3d& pose) { return pose.matrix().allFinite(); }

Status ValidateGnss(const GnssOptions& gnss) {
  if (!(std::abs(gnss.origin.latitude_deg) < 89.0)) {
    return FieldError("gnss.origin.latitude_deg", gnss.origin.latitude_deg, "outside (-89, 89)");
  }
  if (!(std::abs(gnss.origin.longitude_deg) <= 180.0)) {
    return FieldError("gnss.origin.longitude_deg", gnss.origin.longitude_deg,
                      "outside [-180, 180]");
  }
  if (!(gnss.horizontal_sigma_m >= 0.0 && gnss.horizontal_sigma_m < 1000.0)) {
    return FieldError("gnss.horizontal_sigma_m", gnss.horizontal_sigma_m, "outside [0, 1000)");
  }
  if (!(gnss.rtk_sigma_m >= 0.0 && gnss.rtk_sigma_m < 1000.0)) {
    return FieldError("gnss.rtk_sigma_m", gnss.rtk_sigma_m, "outside [0, 1000)");
  }
  if (!(gnss.sentence_latency_s >= 0.0 && gnss.sentence_latency_s < 1.0)) {
    return FieldError("gnss.sentence_latency_s", gnss.sentence_latency_s, "outside [0, 1)");
  }
  return Status::Ok();
}

}  // namespace

LidarOptions DefaultLidarOptions(Model model) {
  LidarOptions options;
  options.model = model;
  switch (model) {
    case Model::kVlp16:
      options.range_noise_sigma_m = 0.015;
      options.max_range_m = 100.0;
      options.position_period_us = 6859.0;
      break;
    case Model::kHdl32e:
      options.range_noise_sigma_m = 0.010;
      options.max_range_m = 100.0;
      options.position_period_us = 4870.0;
      break;
    case Model::kVlp32c:
      options.range_noise_sigma_m = 0.015;
      options.max_range_m = 200.0;
      options.position_period_us = 6859.0;  // no VLP-32C capture with position packets
      break;
  }
  return options;
}

velodyne::LaserTable LaserTableOf(const LidarOptions& options) {
  return options.laser_table ? *options.laser_table : velodyne::DefaultLaserTable(options.model);
}

Status ValidateLidarOptions(const LidarOptions& options) {
  if (!velodyne::ReturnModeFromByte(static_cast<std::uint8_t>(options.return_mode))) {
    return MakeError("lidar options: unknown return_mode");
  }
  const velodyne::LaserTable table = LaserTableOf(options);
  if (table.model != options.model) return MakeError("lidar options: laser_table is of another model");
  if (table.num_lasers != velodyne::LaserCount(options.model) || !(table.distance_resolution_m > 0.0)) {
    return MakeError("lidar options: laser_table has a wrong laser count or resolution");
  }
  if (!(options.rotation_hz >= 5.0 && options.rotation_hz <= 20.0)) {
    return FieldError("rotation_hz", options.rotation_hz, "outside [5, 20]");
  }
  if (!std::isfinite(options.start_azimuth_deg)) {
    return FieldError("start_azimuth_deg", options.start_azimuth_deg, "is not finite");
  }
  if (!IsFiniteIsometry(options.vehicle_T_sensor)) {
    return MakeError("lidar options: vehicle_T_sensor is not finite");
  }
  if (!(options.range_noise_sigma_m >= 0.0 && options.range_noise_sigma_m <= 1.0)) {
    return FieldError("range_noise_sigma_m", options.range_noise_sigma_m, "outside [0, 1]");
  }
  if (!(options.dropout_probability >= 0.0 && options.dropout_probability <= 1.0)) {
    return FieldError("dropout_probability", options.dropout_probability, "outside [0, 1]");
  }
  if (!(options.min_range_m >= 0.0 && options.min_range_m < options.max_range_m)) {
    return FieldError("min_range_m", options.min_range_m, "not in [0, max_range_m)");
  }
  if (!(options.max_range_m <= LargestEncodableRange(table))) {
    return FieldError("max_range_m", options.max_range_m,
                      "beyond what a packet encodes (" + std::to_string(LargestEncodableRange(table)) + " m)");
  }
  if (!(options.start_epoch_ns >= 0)) return MakeError("lidar options: start_epoch_ns is negative");
  if (!(options.start_drive_time_s >= 0.0 && options.start_drive_time_s < 1e7)) {
    return FieldError("start_drive_time_s", options.start_drive_time_s, "outside [0, 1e7)");
  }
  if (!(options.capture_latency_us >= 0.0 && options.capture_latency_us < 1e6)) {
    return FieldError("capture_latency_us", options.capture_latency_us, "outside [0, 1e6)");
  }
  if (!(options.position_period_us >= 100.0 && options.position_period_us <= 1e6)) {
    return FieldError("position_period_us", options.position_period_us, "outside [100, 1e6]");
  }
  return ValidateGnss(options.gnss);
}

}  // namespace flat2d::hal::sim
