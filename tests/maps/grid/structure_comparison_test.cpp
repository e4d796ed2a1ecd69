#include "maps/grid/structure_comparison.hpp"

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

// Truth: a 2 m x 1 m solid block (20 x 10 cells) centred in a 10 m square at 0.1 m.
ClassGrid Truth() {
  ClassGrid truth(GridGeometry{.width = 100, .height = 100, .resolution_m = 0.1, .origin = Eigen::Vector2d(0, 0)});
  for (int row = 45; row < 55; ++row) {
    for (int col = 40; col < 60; ++col) truth.Mark(CellIndex{col, row}, CellClass::kSlammable);
  }
  return truth;
}

TEST(StructureComparison, SouthFaceSeenShiftedByOneCell) {
  const ClassGrid truth = Truth();
  // The grid saw the block's south face (row 45) from the south, one cell too low (row 44),
  // plus free ground in front and one false wall far away. Same frame, half the cell size.
  ClassGrid grid(GridGeometry{.width = 200, .height = 200, .resolution_m = 0.05, .origin = Eigen::Vector2d(0, 0)});
  for (int i = 0; i < 40; ++i) grid.Mark(Eigen::Vector2d(4.01 + 0.05 * i, 4.45), CellClass::kSlammable);
  for (int i = 0; i < 40; ++i) grid.Mark(Eigen::Vector2d(4.01 + 0.05 * i, 3.0), CellClass::kFree);
  for (int i = 0; i < 20; ++i) grid.Mark(Eigen::Vector2d(1.0, 1.01 + 0.05 * i), CellClass::kSlammable);

  const StructureComparison one = CompareStructure(grid, truth, {.tolerance_cells = 1, .observed_radius_cells = 5});
  EXPECT_EQ(one.grid_structure, 40u + 20u);
  EXPECT_EQ(one.grid_matched, 40u);           // the face, one cell off; not the false wall
  EXPECT_NEAR(one.precision(), 40.0 / 60.0, 1e-12);
  // Faces within 5 truth cells of an observed cell (the grid's face at row 44): the south face
  // (row 45, 20 cells) and the west and east faces' rows 46-49 (4 + 4); not the north face.
  EXPECT_EQ(one.truth_faces, 28u);
  EXPECT_EQ(one.truth_matched, 20u);  // within one cell of row 44: row 45 only

  const StructureComparison exact = CompareStructure(grid, truth, {.tolerance_cells = 0, .observed_radius_cells = 5});
  EXPECT_EQ(exact.grid_matched, 0u);  // one cell off is not exact
  EXPECT_EQ(exact.truth_matched, 0u);
}

TEST(StructureComparison, GridCellsOutsideTheTruthAreCountedApart) {
  const ClassGrid truth = Truth();
  ClassGrid grid(GridGeometry{.width = 10, .height = 10, .resolution_m = 0.1, .origin = Eigen::Vector2d(-5, -5)});
  grid.Mark(CellIndex{0, 0}, CellClass::kSlammable);
  const StructureComparison result = CompareStructure(grid, truth);
  EXPECT_EQ(result.grid_outside, 1u);
  EXPECT_EQ(result.grid_structure, 0u);
  EXPECT_EQ(result.truth_faces, 0u);  // nothing observed near the block
  EXPECT_EQ(result.precision(), 0.0);
}

}  // namespace
}  // namespace flat2d::maps
