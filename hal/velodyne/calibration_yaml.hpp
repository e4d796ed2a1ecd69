// Reader of the per-laser calibration YAML used by the common Velodyne drivers (ROS
// velodyne_pointcloud "params/*.yaml" and Autoware's nebula "calibration/*.yaml"), mapped
// into a LaserTable (laser_table.hpp documents each field's meaning).
//
// Format: a map with `lasers`, a list of maps {laser_id, rot_correction, vert_correction,
// dist_correction, vert_offset_correction, horiz_offset_correction, dist_correction_x,
// dist_correction_y, focal_distance, focal_slope, min_intensity, max_intensity}, plus the
// optional `num_lasers` and `distance_resolution`. Angles are radians, lengths metres.
// Steps: parse the YAML (yaml-cpp errors become Errors with the line); count the lasers and
// refuse other counts than 16 and 32 (HDL-64E and VLS-128 files name their count); read
// each laser, refusing unknown keys, non-numbers and angles that cannot be radians; check
// that laser_id covers 0..n-1 once each; pick the model: the given one, else 16 lasers ->
// VLP-16, 32 -> VLP-32C if any rot_correction is non-zero (its lasers sit at azimuth
// offsets, VLP-32C manual 63-9325 Table 9-1), else HDL-32E. Fields not given stay zero;
// without distance_resolution the model's default applies. LaserTable has no place for
// dist_correction_x/y, focal_distance/slope and min/max_intensity: they are validated and
// dropped.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

// Reads and parses a calibration file; errors name the file, line, laser and field.
Result<LaserTable> LoadCalibrationYaml(const std::filesystem::path& path,
                                       std::optional<Model> model);

// Parses calibration text; `source_name` prefixes error messages (usually the file name).
Result<LaserTable> ParseCalibrationYaml(std::string_view text, std::string_view source_name,
                                        std::optional<Model> model);

}  // namespace flat2d::hal::velodyne
