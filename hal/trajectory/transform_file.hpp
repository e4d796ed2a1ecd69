// Rigid transforms as registration tools exchange them: a text file with a 4x4 (or the top
// 3x4 of a) homogeneous matrix, whitespace separated, row-major ('#' comments), as the
// fast_gicp / small_gicp reference files and KITTI's pose lines.
//
// The rotation block must be orthonormal within 1e-4 (a reference that is not a rotation
// is an error, not something to guess at); the bottom row of a 4x4 must be 0 0 0 1.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"

namespace flat2d::hal::trajectory {

Result<Eigen::Isometry3d> ReadTransformFile(const std::filesystem::path& path);
Result<Eigen::Isometry3d> ParseTransform(std::string_view text, std::string_view source_name);

// The 4x4 matrix as four lines of four numbers (%.9g), the format ReadTransformFile reads.
std::string FormatTransform(const Eigen::Isometry3d& transform);

}  // namespace flat2d::hal::trajectory
