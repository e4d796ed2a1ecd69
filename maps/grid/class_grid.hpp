// A 2D grid of CellClass (cell_class.hpp): the structure grid of one revolution or of a
// whole drive, and the raster the hole fill-in and the free-space ray casting draw into.
//
// Marking keeps the strongest class a cell has seen (cell_class.hpp); lines are rasterized
// with Bresenham's algorithm over the cells between two points, ends included. Sized once;
// nothing allocates after construction.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "maps/grid/cell_class.hpp"
#include "maps/grid/grid_geometry.hpp"

namespace flat2d::maps {

class ClassGrid {
 public:
  explicit ClassGrid(const GridGeometry& geometry);

  CellClass at(const CellIndex& cell) const { return cells_[geometry_.Offset(cell)]; }
  // Raises the cell to `cell_class` if that is stronger; false outside the grid.
  bool Mark(const Eigen::Vector2d& point, CellClass cell_class);
  void Mark(const CellIndex& cell, CellClass cell_class);
  // Marks every cell on the segment from a to b (clipped to the grid).
  void MarkLine(Eigen::Vector2d a, Eigen::Vector2d b, CellClass cell_class);
  void Clear();

  const GridGeometry& geometry() const { return geometry_; }
  std::span<const CellClass> cells() const { return cells_; }
  std::size_t Count(CellClass cell_class) const;

 private:
  GridGeometry geometry_;
  std::vector<CellClass> cells_;  // geometry_.cell_count(), row-major, row 0 = lowest y
};

}  // namespace flat2d::maps
