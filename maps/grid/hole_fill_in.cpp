#include "maps/grid/hole_fill_in.hpp"

#include <algorithm>

namespace flat2d::maps {

int FillIn(const ClassifiedFan& previous, const ClassifiedFan& current, double max_gap_m, ClassGrid& grid) {
  const std::size_t lasers = std::min(previous.classes.size(), current.classes.size());
  const double max_gap_squared = max_gap_m * max_gap_m;
  int drawn = 0;
  for (std::size_t laser = 0; laser < lasers; ++laser) {
    const CellClass cell_class = current.classes[laser];
    if (cell_class != previous.classes[laser]) continue;
    if (cell_class != CellClass::kHazard && cell_class != CellClass::kSlammable) continue;
    const Eigen::Vector2d& a = previous.positions[laser];
    const Eigen::Vector2d& b = current.positions[laser];
    if ((b - a).squaredNorm() >= max_gap_squared) continue;
    grid.MarkLine(a, b, cell_class);
    ++drawn;
  }
  return drawn;
}

}  // namespace flat2d::maps
