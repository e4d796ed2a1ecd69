// How well a structure grid finds the true structure (issue 6 acceptance; `flat2d-eval grid`):
// precision and recall of slammable cells within a tolerance of cells.
//
// precision: of the grid's slammable cells, the fraction with a truth slammable (occupied)
//   cell within `tolerance` cells (Chebyshev distance, in the truth's cells).
// recall: of the truth's structure faces the drive could see, the fraction with a grid
//   slammable cell within `tolerance`. A face is an occupied truth cell with a non-occupied
//   4-neighbour; it could be seen when the grid observed (any class but unknown) a cell in
//   front of it on that open side: within `observed_radius` cells of the point
//   observed_radius + 1 cells out. So the back of a wall, whose front the drive saw, does not
//   count as missed structure, nor does a building's far side (a looser "observed anywhere
//   within 1 m" would count both: walls are thinner than that).
// Both grids are in one world frame; grid cells are mapped to the truth cell holding their
// centre, so resolutions and origins may differ. Box queries use integral images: linear time.
#pragma once

#include <cstddef>

#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

struct StructureComparisonOptions {
  int tolerance_cells = 1;
  int observed_radius_cells = 2;  // 10 cm at 5 cm: thinner than any wall
};

struct StructureComparison {
  std::size_t grid_structure = 0;   // slammable cells in the grid (inside the truth's extent)
  std::size_t grid_matched = 0;     // ... near true structure
  std::size_t truth_faces = 0;      // visible faces of the true structure
  std::size_t truth_matched = 0;    // ... near grid structure
  std::size_t grid_outside = 0;     // grid slammable cells outside the truth's extent (not counted)
  double precision() const { return grid_structure == 0 ? 0.0 : static_cast<double>(grid_matched) / grid_structure; }
  double recall() const { return truth_faces == 0 ? 0.0 : static_cast<double>(truth_matched) / truth_faces; }
};

StructureComparison CompareStructure(const ClassGrid& grid, const ClassGrid& truth,
                                     const StructureComparisonOptions& options = {});

}  // namespace flat2d::maps
