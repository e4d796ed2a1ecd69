// The map a scan is matched against: a 2D grid whose cells are either structure (walls,
// poles, kerbs: what a scan point lands on) or not.
//
// It is deliberately minimal, the common denominator of what feeds the matcher: the
// structure-grid tiles of maps/ (converted cell by cell with FromClassCells), a map built
// from points (FromPoints, e.g. a reference laser scan in tests), or a local grid whose
// frame is the vehicle's (ScanPoints::AddGridCells). Cell (0, 0) is the one whose lower-left
// corner is at `origin`; x is the column, y the row, both growing with the world axes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"

namespace flat2d::localization {

struct GridGeometry {
  int width = 0;                               // cells along x
  int height = 0;                              // cells along y
  double resolution = 0.05;                    // cell side, metres
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // world position of cell (0, 0)'s corner

  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  // The cell holding world point `p` (may lie outside the grid).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d CellCenter(int x, int y) const;
  std::size_t CellCount() const { return static_cast<std::size_t>(width) * height; }
};

// Checks what every grid needs: positive size and finite positive resolution and origin.
Status ValidateGeometry(const GridGeometry& geometry);

class MatchGrid {
 public:
  // An empty (no structure) grid; `geometry` must be valid (ValidateGeometry).
  explicit MatchGrid(const GridGeometry& geometry);

  // Row-major class cells (index y * width + x); a cell is structure when its class equals
  // `structure_class`. Fails when the span does not hold exactly width * height cells.
  static Result<MatchGrid> FromClassCells(const GridGeometry& geometry,
                                          std::span<const std::uint8_t> classes,
                                          std::uint8_t structure_class);
  // Marks the cell of each finite point inside the grid; others are ignored.
  static Result<MatchGrid> FromPoints(const GridGeometry& geometry,
                                      std::span<const Eigen::Vector2d> points);

  const GridGeometry& geometry() const { return geometry_; }
  int width() const { return geometry_.width; }
  int height() const { return geometry_.height; }
  double resolution() const { return geometry_.resolution; }

  bool Occupied(int x, int y) const {
    return geometry_.Contains(x, y) && cells_[Index(x, y)] != 0;
  }
  void SetOccupied(int x, int y, bool occupied = true);
  // Clears every cell and moves the grid to `origin`, keeping its size (no allocation): a
  // window that follows the vehicle over a larger map.
  void Reset(const Eigen::Vector2d& origin);
  // Marks the cell of world point `p`; false when it falls outside the grid.
  bool MarkPoint(const Eigen::Vector2d& p);
  std::size_t OccupiedCount() const;

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(geometry_.width) +
           static_cast<std::size_t>(x);
  }

  GridGeometry geometry_;
  std::vector<std::uint8_t> cells_;  // 1 = structure
};

}  // namespace flat2d::localization
