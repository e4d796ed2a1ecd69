// Reading trajectories in the TUM RGB-D benchmark format (Sturm et al. 2012), the field's
// plain-text format for ground truth and estimates: one line "t x y z qx qy qz qw" per pose,
// t in seconds, '#' comments. The simulator writes its truth this way and flat2d-grid,
// flat2d-eval and the localizer read it.
//
// Every malformed line is an error naming the file and line (a truth file that lies is worse
// than none); times must increase; quaternions are normalized (within 1e-3 of unit length,
// else an error).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::trajectory {

struct StampedPose {
  TimeNs time_ns = 0;
  Eigen::Isometry3d world_T_body = Eigen::Isometry3d::Identity();
};

Result<std::vector<StampedPose>> ReadTum(const std::filesystem::path& path);
// The same for text in memory; `source_name` starts error messages.
Result<std::vector<StampedPose>> ParseTum(std::string_view text, std::string_view source_name);

// Writes poses as TUM lines (time with nanosecond digits, positions to 0.1 um, unit
// quaternions with w >= 0); an error names the file if it cannot be written.
Status WriteTum(const std::vector<StampedPose>& poses, const std::filesystem::path& path);

}  // namespace flat2d::hal::trajectory
