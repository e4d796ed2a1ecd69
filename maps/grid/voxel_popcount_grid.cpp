#include "maps/grid/voxel_popcount_grid.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::maps {

VoxelPopcountGrid::VoxelPopcountGrid(const GridGeometry& geometry, float band_height_m)
    : geometry_(geometry), band_height_m_(band_height_m), columns_(geometry.cell_count()) {
  touched_.reserve(columns_.size());
}

bool VoxelPopcountGrid::Add(const Eigen::Vector3f& point) {
  if (!std::isfinite(point.z())) return false;
  const auto cell = geometry_.CellOf(point.head<2>().cast<double>());
  if (!cell) return false;
  const std::size_t offset = geometry_.Offset(*cell);
  VoxelColumn& column = columns_[offset];
  if (column.empty()) touched_.push_back(static_cast<std::uint32_t>(offset));
  AddHeight(column, point.z(), band_height_m_);
  return true;
}

void VoxelPopcountGrid::Clear() {
  for (const std::uint32_t offset : touched_) columns_[offset] = VoxelColumn{};
  touched_.clear();
}

}  // namespace flat2d::maps
