#include "localization/odometry/odometry_config.hpp"

#include "hal/config/text_proto.hpp"

namespace flat2d::localization {

Result<OdometryConfig> LoadOdometryConfig(const std::filesystem::path& path) {
  OdometryConfig config;
  if (Status status = hal::config::LoadTextProto(path, config); !status.ok()) return status.error();
  if (!config.has_mapping()) return MakeError(path.string() + ": no mapping { ... } section");
  if (!config.has_dead_reckoning()) return MakeError(path.string() + ": no dead_reckoning { ... } section");
  Result<DeadReckoningOptions> options = DeadReckoningOptionsFrom(config.dead_reckoning());
  if (!options.ok()) return MakeError(path.string() + ": " + options.error().message);
  return config;
}

Result<DeadReckoningOptions> DeadReckoningOptionsFrom(const DeadReckoningConfig& config) {
  if (!(config.wheel_base_m() > 0.0)) return MakeError("dead_reckoning.wheel_base_m: must be positive");
  if (!(config.track_m() > 0.0)) return MakeError("dead_reckoning.track_m: must be positive");
  DeadReckoningOptions options;
  options.wheel_base_m = config.wheel_base_m();
  options.track_m = config.track_m();
  options.speed_wheels = config.speed_wheels() == DeadReckoningConfig::SPEED_WHEELS_ALL
                             ? SpeedWheels::kAll
                             : SpeedWheels::kRear;
  if (config.has_speed_noise_m_per_sqrt_s()) options.speed_noise_m_per_sqrt_s = config.speed_noise_m_per_sqrt_s();
  if (config.has_wheel_speed_noise_m_per_sqrt_s()) {
    options.wheel_speed_noise_m_per_sqrt_s = config.wheel_speed_noise_m_per_sqrt_s();
  }
  if (config.has_yaw_rate_noise_rad_per_sqrt_s()) {
    options.yaw_rate_noise_rad_per_sqrt_s = config.yaw_rate_noise_rad_per_sqrt_s();
  }
  if (config.has_yaw_rate_bias_radps()) options.yaw_rate_bias_radps = config.yaw_rate_bias_radps();
  options.estimate_yaw_rate_bias = config.estimate_yaw_rate_bias();
  if (config.has_max_gap_s()) options.max_gap_ns = static_cast<TimeNs>(config.max_gap_s() * 1e9);
  if (config.has_wheel_speed_scale()) options.wheel_speed_scale = config.wheel_speed_scale();
  if (Status valid = ValidateOptions(options); !valid.ok()) {
    return MakeError("dead_reckoning: " + valid.error().message);
  }
  return options;
}

}  // namespace flat2d::localization
