#include "maps/grid/class_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace flat2d::maps {

namespace {

// Liang-Barsky: clips the segment a-b to the box [lo, hi]; false when it misses the box.
// Keeps the rasterized line bounded by the grid, however far outside its ends are.
bool ClipToBox(Eigen::Vector2d& a, Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    const double p[2] = {-d[axis], d[axis]};
    const double q[2] = {a[axis] - lo[axis], hi[axis] - a[axis]};
    for (int side = 0; side < 2; ++side) {
      if (p[side] == 0.0) {
        if (q[side] < 0.0) return false;
        continue;
      }
      const double t = q[side] / p[side];
      if (p[side] < 0.0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
    }
  }
  if (t0 > t1) return false;
  const Eigen::Vector2d start = a + t0 * d;
  b = a + t1 * d;
  a = start;
  return true;
}

}  // namespace

ClassGrid::ClassGrid(const GridGeometry& geometry)
    : geometry_(geometry), cells_(geometry.cell_count(), CellClass::kUnknown) {}

void ClassGrid::Mark(const CellIndex& cell, CellClass cell_class) {
  CellClass& stored = cells_[geometry_.Offset(cell)];
  stored = Strongest(stored, cell_class);
}

bool ClassGrid::Mark(const Eigen::Vector2d& point, CellClass cell_class) {
  const auto cell = geometry_.CellOf(point);
  if (!cell) return false;
  Mark(*cell, cell_class);
  return true;
}

void ClassGrid::MarkLine(Eigen::Vector2d a, Eigen::Vector2d b, CellClass cell_class) {
  if (!a.allFinite() || !b.allFinite()) return;
  const Eigen::Vector2d extent = geometry_.resolution_m * Eigen::Vector2d(geometry_.width, geometry_.height);
  if (!ClipToBox(a, b, geometry_.origin, geometry_.origin + extent)) return;
  // Cell coordinates without bounds: the line may start or end outside the grid.
  auto cell_coordinates = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2i(static_cast<int>(std::floor((p.x() - geometry_.origin.x()) / geometry_.resolution_m)),
                           static_cast<int>(std::floor((p.y() - geometry_.origin.y()) / geometry_.resolution_m)));
  };
  Eigen::Vector2i from = cell_coordinates(a);
  const Eigen::Vector2i to = cell_coordinates(b);
  const int dx = std::abs(to.x() - from.x());
  const int dy = -std::abs(to.y() - from.y());
  const int step_x = from.x() < to.x() ? 1 : -1;
  const int step_y = from.y() < to.y() ? 1 : -1;
  int error = dx + dy;
  while (true) {
    const CellIndex cell{from.x(), from.y()};
    if (geometry_.Contains(cell)) Mark(cell, cell_class);
    if (from == to) break;
    const int doubled = 2 * error;
    if (doubled >= dy) error += dy, from.x() += step_x;
    if (doubled <= dx) error += dx, from.y() += step_y;
  }
}

void ClassGrid::Clear() { std::fill(cells_.begin(), cells_.end(), CellClass::kUnknown); }

std::size_t ClassGrid::Count(CellClass cell_class) const {
  return static_cast<std::size_t>(std::count(cells_.begin(), cells_.end(), cell_class));
}

}  // namespace flat2d::maps
