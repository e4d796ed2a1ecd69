// The Scene's acceleration structure (internal): a uniform 2D grid over XY whose cells list
// the static solids and ramps whose footprints touch them, walked along a ray with the
// 2D DDA of Amanatides and Woo ("A fast voxel traversal algorithm", 1987).
//
// Steps of a walk: clip the ray's XY projection to the grid, find the first cell, then
// step to whichever neighbouring cell boundary (x or y) the ray crosses first. The caller's
// visitor tests the cell's solids and returns the nearest hit so far; the walk stops as soon
// as that hit lies within the current cell, since no later cell can hold a nearer surface.
// Each cell also stores the top of its tallest solid, so a ray passing above a cell skips
// it without testing anything. Lane markings have a grid of their own with the same cells.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/sim/scene_compile.hpp"
#include "hal/sim/scene_primitives.hpp"

namespace flat2d::hal::sim::internal {

// A reference to a solid: its kind in the top 4 bits, its index in that kind's array below.
enum class RefKind : std::uint32_t { kBox = 0, kCylinder = 1, kPrism = 2, kFoliage = 3, kRamp = 4 };
inline constexpr std::uint32_t kRefIndexBits = 28;
inline constexpr std::uint32_t MakeRef(RefKind kind, std::size_t index) {
  return (static_cast<std::uint32_t>(kind) << kRefIndexBits) | static_cast<std::uint32_t>(index);
}
inline constexpr RefKind KindOf(std::uint32_t ref) {
  return static_cast<RefKind>(ref >> kRefIndexBits);
}
inline constexpr std::uint32_t IndexOf(std::uint32_t ref) {
  return ref & ((1U << kRefIndexBits) - 1U);
}

struct GridCell {
  std::span<const std::uint32_t> refs;
  double top_z = -kInfinity;  // highest point of any solid in the cell
};

class SceneGrid {
 public:
  SceneGrid() = default;
  // Cells of about `cell_size_m` (larger if the bounds would need more than `max_cells`).
  static SceneGrid Build(const CompiledStatics& statics, const Eigen::AlignedBox2d& bounds,
                         double cell_size_m, std::size_t max_cells);

  // The cell under (x, y); empty outside the grid.
  GridCell CellAt(double x, double y) const;
  std::span<const std::uint32_t> LanesAt(double x, double y) const;

  // Visits the cells the ray crosses for t in [t_begin, t_end], nearest first:
  // visit(const GridCell&, t_enter, t_exit) returns the nearest hit so far (or t_end).
  template <typename Visit>
  void Walk(const Ray& ray, double t_begin, double t_end, Visit&& visit) const;

  double cell_size() const { return cell_; }

 private:
  GridCell Cell(int index) const {
    const auto i = static_cast<std::size_t>(index);
    return {std::span<const std::uint32_t>(refs_).subspan(offsets_[i], offsets_[i + 1] - offsets_[i]),
            top_z_[i]};
  }
  int IndexAt(double x, double y) const;  // -1 outside

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  double inv_cell_ = 1.0;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::uint32_t> offsets_;  // CSR: refs_ of cell i are [offsets_[i], offsets_[i+1])
  std::vector<std::uint32_t> refs_;
  std::vector<double> top_z_;
  std::vector<std::uint32_t> lane_offsets_;
  std::vector<std::uint32_t> lane_refs_;
};

template <typename Visit>
void SceneGrid::Walk(const Ray& ray, double t_begin, double t_end, Visit&& visit) const {
  if (nx_ == 0) return;
  const double ox = ray.origin.x();
  const double oy = ray.origin.y();
  const double dx = ray.direction.x();
  const double dy = ray.direction.y();
  double t0 = t_begin;
  double t1 = t_end;
  bool entered = false;
  bool left = false;
  const double x_max = origin_.x() + nx_ * cell_;
  const double y_max = origin_.y() + ny_ * cell_;
  if (!ClipSlab(ox, dx, origin_.x(), x_max, t0, t1, entered, left) ||
      !ClipSlab(oy, dy, origin_.y(), y_max, t0, t1, entered, left)) {
    return;
  }
  int ix = std::clamp(static_cast<int>(std::floor((ox + t0 * dx - origin_.x()) * inv_cell_)), 0,
                      nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((oy + t0 * dy - origin_.y()) * inv_cell_)), 0,
                      ny_ - 1);
  const bool x_moves = std::abs(dx) >= kParallelEpsilon;
  const bool y_moves = std::abs(dy) >= kParallelEpsilon;
  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  double t_next_x =
      x_moves ? (origin_.x() + (ix + (dx > 0.0 ? 1 : 0)) * cell_ - ox) / dx : kInfinity;
  double t_next_y =
      y_moves ? (origin_.y() + (iy + (dy > 0.0 ? 1 : 0)) * cell_ - oy) / dy : kInfinity;
  const double t_delta_x = x_moves ? cell_ / std::abs(dx) : kInfinity;
  const double t_delta_y = y_moves ? cell_ / std::abs(dy) : kInfinity;
  double t_enter = t0;
  while (true) {
    const double t_exit = std::min(std::min(t_next_x, t_next_y), t1);
    t1 = std::min(t1, visit(Cell(iy * nx_ + ix), t_enter, t_exit));
    if (t1 <= t_exit) return;
    if (t_next_x < t_next_y) {
      ix += step_x;
      if (ix < 0 || ix >= nx_) return;
      t_enter = t_next_x;
      t_next_x += t_delta_x;
    } else {
      iy += step_y;
      if (iy < 0 || iy >= ny_) return;
      t_enter = t_next_y;
      t_next_y += t_delta_y;
    }
  }
}

}  // namespace flat2d::hal::sim::internal
