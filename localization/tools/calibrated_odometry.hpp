// The vehicle's odometry configuration with the wheel scale a map build measured
// (`flat2d-map build --calibrated-odometry-out`), for flat2d-localize and flat2dd on the same
// vehicle: the scale the builder's odometry factors ended at, times the GNSS track's
// correction, times the scale the configuration already had (the builder measured relative
// to it).
#pragma once

#include <filesystem>

#include "hal/common/error.hpp"

namespace flat2d::localization {

// Reads `odometry_config`, sets dead_reckoning.wheel_speed_scale and writes it to `out`
// (text format, with a comment saying where the scale came from). Errors name the file.
Status WriteCalibratedOdometry(const std::filesystem::path& odometry_config, double odometry_scale,
                               double track_scale, const std::filesystem::path& out);

}  // namespace flat2d::localization
