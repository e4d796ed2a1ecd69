// Reading KITTI Velodyne scans (.bin, Geiger et al. 2012): no header, N records of four
// little-endian float32, x y z in metres in the Velodyne frame (x forward, y left, z up)
// and the reflectance 0..1, which becomes the intensity. A size that is not a multiple of
// 16 bytes is a damaged file (a cut download, a text transfer), an error naming the file
// and its size.
#pragma once

#include <filesystem>
#include <string_view>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

Result<PointCloud> ReadKittiBin(const std::filesystem::path& path);
// The same for bytes in memory; `source_name` starts error messages.
Result<PointCloud> ParseKittiBin(std::string_view bytes, std::string_view source_name);

}  // namespace flat2d::hal::cloud
