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
  // Faces with observed cells in front of them (rows 39-44 hold the grid's face at row 44):
  // the south face (row 45, 20 cells); not the west and east faces, in front of which
  // (columns 29-39 and 60-70) nothing was observed, nor the north face.
  EXPECT_EQ(one.truth_faces, 20u);
  EXPECT_EQ(one.truth_matched, 20u);  // within one cell of row 44: row 45 only

  const StructureComparison exact = CompareStructure(grid, truth, {.tolerance_cells = 0, .observed_radius_cells = 5});
  EXPECT_EQ(exact.grid_matched, 0u);  // one cell off is not exact
  EXPECT_EQ(exact.truth_matched, 0u);
}

TEST(StructureComparison, TheBackOfAWallSeenFromTheFrontIsNotMissed) {
  // A wall 2 cells thick (rows 50-51) across a 10 m square at 0.1 m; the grid saw its south
  // face from the south (free up to row 49, structure on row 50) and nothing north of it.
  ClassGrid truth(GridGeometry{.width = 100, .height = 100, .resolution_m = 0.1, .origin = Eigen::Vector2d(0, 0)});
  ClassGrid grid(truth.geometry());
  for (int col = 0; col < 100; ++col) {
    truth.Mark(CellIndex{col, 50}, CellClass::kSlammable);
    truth.Mark(CellIndex{col, 51}, CellClass::kSlammable);
    grid.Mark(CellIndex{col, 50}, CellClass::kSlammable);
    for (int row = 30; row < 50; ++row) grid.Mark(CellIndex{col, row}, CellClass::kFree);
  }
  const StructureComparison result = CompareStructure(grid, truth, {.tolerance_cells = 1, .observed_radius_cells = 2});
  EXPECT_EQ(result.truth_faces, 100u);  // row 50 only: row 51's front (rows 52-56) is unseen
  EXPECT_EQ(result.truth_matched, 100u);
  EXPECT_DOUBLE_EQ(result.recall(), 1.0);
  EXPECT_DOUBLE_EQ(result.precision(), 1.0);
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
