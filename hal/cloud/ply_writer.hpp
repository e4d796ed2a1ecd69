// Writing point clouds as PLY (binary_little_endian 1.0): vertex x y z and, when given,
// nx ny nz, the format ReadPly and every mesh viewer (MeshLab, CloudCompare) read.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

// `normals` empty or one per point. An error names the file if it cannot be written.
Status WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3f>& points,
                const std::vector<Eigen::Vector3f>& normals);

}  // namespace flat2d::hal::cloud
