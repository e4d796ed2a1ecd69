#include "localization/tools/calibrated_odometry.hpp"

#include <cstdio>
#include <fstream>
#include <string>

#include <google/protobuf/text_format.h>

#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization {

Status WriteCalibratedOdometry(const std::filesystem::path& odometry_config, double odometry_scale,
                               double track_scale, const std::filesystem::path& out) {
  auto config = LoadOdometryConfig(odometry_config);
  if (!config.ok()) return config.error();
  DeadReckoningConfig& dr = *config->mutable_dead_reckoning();
  const double given = dr.has_wheel_speed_scale() ? dr.wheel_speed_scale() : 1.0;
  const double measured = given * odometry_scale * track_scale;
  dr.set_wheel_speed_scale(measured);
  std::string text;
  if (!google::protobuf::TextFormat::PrintToString(*config, &text)) return MakeError("cannot format " + out.string());
  char scales[160];
  std::snprintf(scales, sizeof scales, "%.6f (odometry %.6f x track %.6f x given %.6f)", measured, odometry_scale,
                track_scale, given);
  std::ofstream file(out);
  file << "# " << odometry_config.string() << " with the wheel scale measured by flat2d-map build: " << scales
       << "\n# proto-file: localization/odometry/odometry_config.proto\n"
       << "# proto-message: flat2d.localization.OdometryConfig\n"
       << text;
  if (!file.flush()) return MakeError("cannot write " + out.string());
  return Status::Ok();
}

}  // namespace flat2d::localization
