#include "maps/grid/grid_crop.hpp"

#include <algorithm>

namespace flat2d::maps {

std::optional<ClassGrid> CropToObserved(const ClassGrid& grid, int margin_cells) {
  const GridGeometry& g = grid.geometry();
  int col_min = g.width, col_max = -1, row_min = g.height, row_max = -1;
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (grid.at({col, row}) == CellClass::kUnknown) continue;
      col_min = std::min(col_min, col);
      col_max = std::max(col_max, col);
      row_min = std::min(row_min, row);
      row_max = std::max(row_max, row);
    }
  }
  if (col_max < 0) return std::nullopt;
  col_min = std::max(0, col_min - margin_cells);
  row_min = std::max(0, row_min - margin_cells);
  col_max = std::min(g.width - 1, col_max + margin_cells);
  row_max = std::min(g.height - 1, row_max + margin_cells);

  GridGeometry cropped = g;
  cropped.width = col_max - col_min + 1;
  cropped.height = row_max - row_min + 1;
  cropped.origin = g.origin + g.resolution_m * Eigen::Vector2d(col_min, row_min);
  ClassGrid out(cropped);
  for (int row = 0; row < cropped.height; ++row) {
    for (int col = 0; col < cropped.width; ++col) {
      out.Mark(CellIndex{col, row}, grid.at({col + col_min, row + row_min}));
    }
  }
  return out;
}

}  // namespace flat2d::maps
