// The odometry configuration file: protobuf text format (odometry_config.proto) into the
// signal mapping and the dead-reckoning options, checked field by field.
#pragma once

#include <filesystem>

#include "hal/common/error.hpp"
#include "localization/odometry/dead_reckoning.hpp"
#include "localization/odometry/odometry_config.pb.h"

namespace flat2d::localization {

// Reads the file; errors give file, line and field.
Result<OdometryConfig> LoadOdometryConfig(const std::filesystem::path& path);

// The options the configuration gives; fields it leaves unset keep DeadReckoningOptions'
// documented values. Errors name the field.
Result<DeadReckoningOptions> DeadReckoningOptionsFrom(const DeadReckoningConfig& config);

}  // namespace flat2d::localization
