#include "maps/grid/voxel_column.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::maps {

void AddHeight(VoxelColumn& column, float z, float band_height_m) {
  if (column.empty()) {
    column.z_min = z;
    column.bands = 1;
    return;
  }
  if (z < column.z_min) {
    const float shift = std::ceil((column.z_min - z) / band_height_m);
    if (shift >= static_cast<float>(kVoxelBands)) {
      column.bands = 0;  // every earlier band is now above the top
    } else {
      column.bands <<= static_cast<int>(shift);
    }
    column.z_min -= shift * band_height_m;
  }
  const float band = std::floor((z - column.z_min) / band_height_m);
  // Rounding can put a return a hair below the new z-min; it belongs to band 0.
  const int index = std::max(0, static_cast<int>(band));
  if (band < static_cast<float>(kVoxelBands)) column.bands |= std::uint64_t{1} << index;
}

std::uint64_t BandMask(float low_m, float high_m, float band_height_m) {
  const int first = static_cast<int>(std::floor(low_m / band_height_m));
  const int last = static_cast<int>(std::ceil(high_m / band_height_m));  // exclusive
  if (first >= kVoxelBands || last <= first) return 0;
  const int count = std::min(last, kVoxelBands) - first;
  const std::uint64_t ones = count == kVoxelBands ? ~std::uint64_t{0} : (std::uint64_t{1} << count) - 1;
  return ones << first;
}

}  // namespace flat2d::maps
