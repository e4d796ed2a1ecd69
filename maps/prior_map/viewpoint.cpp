#include "maps/prior_map/viewpoint.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flat2d::maps {

ClassGrid VisibleFrom(const ClassGrid& mosaic, const Eigen::Vector2d& position, double range_m,
                      double angular_step_rad) {
  const GridGeometry& m = mosaic.geometry();
  // The block of mosaic cells within range_m of the pose, clipped to the mosaic.
  auto clamp_col = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - m.origin.x()) / m.resolution_m)), 0, m.width - 1); };
  auto clamp_row = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - m.origin.y()) / m.resolution_m)), 0, m.height - 1); };
  const int col0 = clamp_col(position.x() - range_m), col1 = clamp_col(position.x() + range_m);
  const int row0 = clamp_row(position.y() - range_m), row1 = clamp_row(position.y() + range_m);
  GridGeometry g;
  g.resolution_m = m.resolution_m;
  g.width = col1 - col0 + 1;
  g.height = row1 - row0 + 1;
  g.origin = m.origin + m.resolution_m * Eigen::Vector2d(col0, row0);
  ClassGrid visible(g);

  const double step = 0.5 * m.resolution_m;  // half a cell: no cell is skipped
  const int samples = static_cast<int>(range_m / step);
  const int rays = static_cast<int>(std::ceil(2.0 * std::numbers::pi / angular_step_rad));
  for (int k = 0; k < rays; ++k) {
    const double angle = k * angular_step_rad;
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    for (int i = 0; i <= samples; ++i) {
      const Eigen::Vector2d p = position + (i * step) * direction;
      const auto cell = m.CellOf(p);
      if (!cell) break;
      const CellClass c = mosaic.at(*cell);
      visible.Mark(p, c);
      if (c == CellClass::kSlammable) break;
    }
  }
  return visible;
}

}  // namespace flat2d::maps
