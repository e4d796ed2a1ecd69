// Planar trajectories as TUM files ("t x y z qx qy qz qw", hal/trajectory): the estimates
// flat2d-map writes and flat2d-eval reads, flattened to (x, y, yaw) on reading.
#pragma once

#include <filesystem>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/evaluation/relations.hpp"

namespace flat2d::localization::evaluation {

Result<std::vector<TimedPose>> ReadTrajectory(const std::filesystem::path& path);
// z = 0, the heading as a rotation about z; times with 9 decimals.
Status WriteTrajectory(const std::vector<TimedPose>& trajectory, const std::filesystem::path& path);

}  // namespace flat2d::localization::evaluation
