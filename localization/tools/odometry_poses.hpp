// A candump log dead-reckoned into poses for the offline tools: the vehicle in the odometry
// ("local") frame at every new odometry sample, as flat2d-can odom writes them, so that
// flat2d-grid can place each fan with the vehicle pose at its own time.
#pragma once

#include <filesystem>
#include <vector>

#include "hal/can/candump_log.hpp"
#include "hal/common/error.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "maps/grid/interpolated_poses.hpp"

namespace flat2d::localization {

// A candump log ready to dead-reckon: its reader and the odometry of the DBC and the
// odometry configuration (each file's errors name it).
struct CanLogOdometry {
  CanOdometry odometry;
  hal::can::CandumpReader reader;
};
Result<CanLogOdometry> OpenCanLogOdometry(const std::filesystem::path& dbc, const std::filesystem::path& odometry_config,
                                          const std::filesystem::path& log);

Result<std::vector<maps::StampedPose2d>> DeadReckonedPoses(const std::filesystem::path& dbc,
                                                           const std::filesystem::path& odometry_config,
                                                           const std::filesystem::path& log);

// A TUM trajectory (truth or estimate) flattened to (x, y, yaw).
Result<std::vector<maps::StampedPose2d>> TumPoses(const std::filesystem::path& tum);

}  // namespace flat2d::localization
