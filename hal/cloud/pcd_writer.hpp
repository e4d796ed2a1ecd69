// Writing point clouds as PCL's PCD v0.7, DATA binary: x y z (F4) and, where the cloud has
// them, intensity (F4) and ring (U2), the channels ReadPcd keeps, in one record per point.
// PCL, Open3D and CloudCompare read it; NaN points stay NaN. An organized cloud (a grid) is
// written unorganized, its points in their order: the grid is the reader's to rebuild.
#pragma once

#include <filesystem>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

// An error names the file if it cannot be written, or the channel whose length is not one
// per point.
Status WritePcd(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace flat2d::hal::cloud
