// What every cloud a reader returns must satisfy, for the cloud readers' fuzz targets:
// channels empty or one value per point, and a grid of grid_width x grid_height cells
// each -1 or the index of a point. A violation aborts, which libFuzzer reports as a crash.
#pragma once

#include <cstdlib>

#include "hal/cloud/point_cloud.hpp"

namespace flat2d::fuzz {

inline void CheckCloud(const hal::cloud::PointCloud& cloud) {
  const std::size_t n = cloud.points.size();
  if (!cloud.intensity.empty() && cloud.intensity.size() != n) std::abort();
  if (!cloud.ring.empty() && cloud.ring.size() != n) std::abort();
  if (!cloud.organized()) {
    if (!cloud.grid.empty()) std::abort();
    return;
  }
  if (cloud.grid.size() != static_cast<std::size_t>(cloud.grid_width) * static_cast<std::size_t>(cloud.grid_height)) {
    std::abort();
  }
  for (const std::int32_t cell : cloud.grid) {
    if (cell < -1 || (cell >= 0 && static_cast<std::size_t>(cell) >= n)) std::abort();
  }
}

}  // namespace flat2d::fuzz
