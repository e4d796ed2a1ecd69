// Where the cells of a 2D grid are: size, resolution and the world position of cell
// (0, 0)'s lower-left corner, as map_server's origin. Cell (col, row) covers
// [origin + col r, origin + (col + 1) r) x [origin + row r, origin + (row + 1) r); row 0 is the
// lowest y (images flip it when written).
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>

#include <Eigen/Core>

namespace flat2d::maps {

struct CellIndex {
  int col = 0;
  int row = 0;
  bool operator==(const CellIndex&) const = default;
};

struct GridGeometry {
  int width = 0;   // columns, along x
  int height = 0;  // rows, along y
  double resolution_m = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();

  std::size_t cell_count() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool Contains(const CellIndex& cell) const {
    return cell.col >= 0 && cell.row >= 0 && cell.col < width && cell.row < height;
  }
  std::size_t Offset(const CellIndex& cell) const {
    return static_cast<std::size_t>(cell.row) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(cell.col);
  }
  // The cell holding `point`, or nullopt outside the grid (or for NaN).
  std::optional<CellIndex> CellOf(const Eigen::Vector2d& point) const {
    const double col = std::floor((point.x() - origin.x()) / resolution_m);
    const double row = std::floor((point.y() - origin.y()) / resolution_m);
    if (!(col >= 0.0 && row >= 0.0 && col < width && row < height)) return std::nullopt;
    return CellIndex{static_cast<int>(col), static_cast<int>(row)};
  }
  Eigen::Vector2d CellCenter(const CellIndex& cell) const {
    return origin + resolution_m * Eigen::Vector2d(cell.col + 0.5, cell.row + 0.5);
  }
};

}  // namespace flat2d::maps
