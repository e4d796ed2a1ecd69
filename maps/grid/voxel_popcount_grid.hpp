// Cartesian compact voxel popcount grid (thesis 7.1.2): a fixed XY grid of VoxelColumns
// (voxel_column.hpp), every return added to the column under it, structure where the
// column's popcount reaches a threshold.
//
// The grid is sized once from its geometry and never reallocates: Add and Clear allocate
// nothing, so a revolution can be accumulated in the daemon's hot path.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "maps/grid/grid_geometry.hpp"
#include "maps/grid/voxel_column.hpp"

namespace flat2d::maps {

class VoxelPopcountGrid {
 public:
  VoxelPopcountGrid(const GridGeometry& geometry, float band_height_m);

  // Adds one return (grid frame); false when it falls outside the grid or is not finite.
  bool Add(const Eigen::Vector3f& point);
  void Clear();

  const VoxelColumn& column(const CellIndex& cell) const { return columns_[geometry_.Offset(cell)]; }
  std::span<const VoxelColumn> columns() const { return columns_; }
  // Offsets of the columns that hold returns, each once, in the order first hit: a
  // revolution touches a few percent of the grid, so classifying and clearing only these
  // keeps the work after the last packet small.
  std::span<const std::uint32_t> touched() const { return touched_; }
  // Popcount of the column's bands within `band_mask` (BandMask) reaches `threshold`.
  bool IsStructure(const CellIndex& cell, int threshold, std::uint64_t band_mask = ~0ULL) const {
    return std::popcount(column(cell).bands & band_mask) >= threshold;
  }

  const GridGeometry& geometry() const { return geometry_; }
  float band_height_m() const { return band_height_m_; }

 private:
  GridGeometry geometry_;
  float band_height_m_;
  std::vector<VoxelColumn> columns_;  // geometry_.cell_count(), row-major
  std::vector<std::uint32_t> touched_;  // capacity cell_count(): every column at most once
};

}  // namespace flat2d::maps
