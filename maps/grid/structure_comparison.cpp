#include "maps/grid/structure_comparison.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace flat2d::maps {
namespace {

// Counts of a mask over boxes of cells in O(1) per query.
class IntegralImage {
 public:
  IntegralImage(const GridGeometry& geometry, const std::vector<std::uint8_t>& mask)
      : width_(geometry.width), height_(geometry.height),
        sums_(static_cast<std::size_t>(width_ + 1) * static_cast<std::size_t>(height_ + 1), 0) {
    for (int row = 0; row < height_; ++row) {
      for (int col = 0; col < width_; ++col) {
        At(col + 1, row + 1) = mask[geometry.Offset({col, row})] + At(col, row + 1) + At(col + 1, row) - At(col, row);
      }
    }
  }
  // Set cells in the box of cells within `radius` of `cell`, clipped to the grid.
  std::int64_t BoxSum(const CellIndex& cell, int radius) const {
    const int c0 = std::max(0, cell.col - radius), c1 = std::min(width_, cell.col + radius + 1);
    const int r0 = std::max(0, cell.row - radius), r1 = std::min(height_, cell.row + radius + 1);
    if (c0 >= c1 || r0 >= r1) return 0;
    return Value(c1, r1) - Value(c0, r1) - Value(c1, r0) + Value(c0, r0);
  }

 private:
  std::int64_t& At(int col, int row) { return sums_[Index(col, row)]; }
  std::int64_t Value(int col, int row) const { return sums_[Index(col, row)]; }
  std::size_t Index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_ + 1) + static_cast<std::size_t>(col);
  }
  int width_;
  int height_;
  std::vector<std::int64_t> sums_;
};

constexpr CellIndex kDirections[] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};

}  // namespace

StructureComparison CompareStructure(const ClassGrid& grid, const ClassGrid& truth,
                                     const StructureComparisonOptions& options) {
  const GridGeometry& t = truth.geometry();
  std::vector<std::uint8_t> mask(t.cell_count(), 0);
  for (std::size_t i = 0; i < t.cell_count(); ++i) mask[i] = truth.cells()[i] == CellClass::kSlammable;
  const IntegralImage truth_structure(t, mask);

  // Precision, and the grid's structure and observed cells resampled onto the truth's cells.
  StructureComparison result;
  std::vector<std::uint8_t> grid_structure(t.cell_count(), 0);
  std::vector<std::uint8_t> observed(t.cell_count(), 0);
  const GridGeometry& g = grid.geometry();
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const CellClass cell_class = grid.at({col, row});
      if (cell_class == CellClass::kUnknown) continue;
      const auto cell = t.CellOf(g.CellCenter({col, row}));
      const bool structure = cell_class == CellClass::kSlammable;
      if (!cell) {
        result.grid_outside += structure;
        continue;
      }
      observed[t.Offset(*cell)] = 1;
      if (!structure) continue;
      grid_structure[t.Offset(*cell)] = 1;
      ++result.grid_structure;
      result.grid_matched += truth_structure.BoxSum(*cell, options.tolerance_cells) > 0;
    }
  }

  // Recall over the faces the grid could have seen: those with observed cells in front of
  // them, on a side where the truth is open.
  const IntegralImage found(t, grid_structure);
  const IntegralImage seen(t, observed);
  const int r = options.observed_radius_cells;
  for (int row = 0; row < t.height; ++row) {
    for (int col = 0; col < t.width; ++col) {
      const CellIndex cell{col, row};
      if (truth.at(cell) != CellClass::kSlammable) continue;
      bool visible = false;
      for (const CellIndex& d : kDirections) {
        const CellIndex open{col + d.col, row + d.row};
        if (!t.Contains(open) || truth.at(open) == CellClass::kSlammable) continue;
        const CellIndex front{col + (r + 1) * d.col, row + (r + 1) * d.row};
        visible = visible || seen.BoxSum(front, r) > 0;
      }
      if (!visible) continue;
      ++result.truth_faces;
      result.truth_matched += found.BoxSum(cell, options.tolerance_cells) > 0;
    }
  }
  return result;
}

}  // namespace flat2d::maps
