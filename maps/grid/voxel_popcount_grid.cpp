#include "maps/grid/voxel_popcount_grid.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::maps {

VoxelPopcountGrid::VoxelPopcountGrid(const GridGeometry& geometry, float band_height_m)
    : geometry_(geometry), band_height_m_(band_height_m), columns_(geometry.cell_count()) {}

bool VoxelPopcountGrid::Add(const Eigen::Vector3f& point) {
  if (!std::isfinite(point.z())) return false;
  const auto cell = geometry_.CellOf(point.head<2>().cast<double>());
  if (!cell) return false;
  AddHeight(columns_[geometry_.Offset(*cell)], point.z(), band_height_m_);
  return true;
}

void VoxelPopcountGrid::Clear() { std::fill(columns_.begin(), columns_.end(), VoxelColumn{}); }

}  // namespace flat2d::maps
