#include "localization/matching/match_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace flat2d::localization {

namespace {

// floor(v) as an int, saturated so that far or non-finite points cannot overflow.
int FloorToCell(double v) {
  constexpr double kLimit = 1.0e9;
  if (!(v > -kLimit)) return -static_cast<int>(kLimit);
  if (!(v < kLimit)) return static_cast<int>(kLimit);
  return static_cast<int>(std::floor(v));
}

}  // namespace

Eigen::Vector2i GridGeometry::CellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d cell = (p - origin) / resolution;
  return {FloorToCell(cell.x()), FloorToCell(cell.y())};
}

Eigen::Vector2d GridGeometry::CellCenter(int x, int y) const {
  return origin + resolution * Eigen::Vector2d(x + 0.5, y + 0.5);
}

Status ValidateGeometry(const GridGeometry& geometry) {
  if (geometry.width <= 0 || geometry.height <= 0) {
    return MakeError("grid size must be positive, got " + std::to_string(geometry.width) + " x " +
                     std::to_string(geometry.height));
  }
  if (!std::isfinite(geometry.resolution) || geometry.resolution <= 0.0) {
    return MakeError("grid resolution must be finite and positive");
  }
  if (!geometry.origin.allFinite()) return MakeError("grid origin must be finite");
  return Status::Ok();
}

MatchGrid::MatchGrid(const GridGeometry& geometry)
    : geometry_(geometry), cells_(geometry.CellCount(), 0) {}

Result<MatchGrid> MatchGrid::FromClassCells(const GridGeometry& geometry,
                                            std::span<const std::uint8_t> classes,
                                            std::uint8_t structure_class) {
  if (Status valid = ValidateGeometry(geometry); !valid) return valid.error();
  if (classes.size() != geometry.CellCount()) {
    return MakeError("class cells: expected " + std::to_string(geometry.CellCount()) +
                     " cells, got " + std::to_string(classes.size()));
  }
  MatchGrid grid(geometry);
  std::transform(classes.begin(), classes.end(), grid.cells_.begin(),
                 [structure_class](std::uint8_t c) { return c == structure_class ? 1 : 0; });
  return grid;
}

Result<MatchGrid> MatchGrid::FromPoints(const GridGeometry& geometry,
                                        std::span<const Eigen::Vector2d> points) {
  if (Status valid = ValidateGeometry(geometry); !valid) return valid.error();
  MatchGrid grid(geometry);
  for (const Eigen::Vector2d& p : points) {
    if (p.allFinite()) grid.MarkPoint(p);
  }
  return grid;
}

void MatchGrid::SetOccupied(int x, int y, bool occupied) {
  if (geometry_.Contains(x, y)) cells_[Index(x, y)] = occupied ? 1 : 0;
}

void MatchGrid::Reset(const Eigen::Vector2d& origin) {
  geometry_.origin = origin;
  std::fill(cells_.begin(), cells_.end(), std::uint8_t{0});
}

bool MatchGrid::MarkPoint(const Eigen::Vector2d& p) {
  const Eigen::Vector2d cell = (p - geometry_.origin) / geometry_.resolution;
  // Compare in double first: a far point would overflow the int conversion.
  if (!(cell.x() >= 0.0 && cell.y() >= 0.0 && cell.x() < geometry_.width &&
        cell.y() < geometry_.height)) {
    return false;
  }
  SetOccupied(static_cast<int>(cell.x()), static_cast<int>(cell.y()));
  return true;
}

std::size_t MatchGrid::OccupiedCount() const {
  return static_cast<std::size_t>(std::count(cells_.begin(), cells_.end(), std::uint8_t{1}));
}

}  // namespace flat2d::localization
