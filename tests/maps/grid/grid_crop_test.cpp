#include "maps/grid/grid_crop.hpp"

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

TEST(GridCrop, KeepsTheObservedCellsWhereTheyWereInTheWorld) {
  ClassGrid grid(GridGeometry{.width = 100, .height = 80, .resolution_m = 0.1, .origin = Eigen::Vector2d(-5, -4)});
  grid.Mark(CellIndex{10, 20}, CellClass::kFree);
  grid.Mark(CellIndex{30, 25}, CellClass::kSlammable);
  grid.Mark(CellIndex{12, 60}, CellClass::kHazard);
  const auto cropped = CropToObserved(grid, 2);
  ASSERT_TRUE(cropped.has_value());
  const GridGeometry& c = cropped->geometry();
  EXPECT_EQ(c.width, 30 - 10 + 1 + 4);
  EXPECT_EQ(c.height, 60 - 20 + 1 + 4);
  EXPECT_NEAR(c.origin.x(), -5 + 0.1 * 8, 1e-12);
  EXPECT_NEAR(c.origin.y(), -4 + 0.1 * 18, 1e-12);
  // Every cell of the original grid has the same class at the same world point.
  for (int row = 0; row < 80; ++row) {
    for (int col = 0; col < 100; ++col) {
      const auto cell = c.CellOf(grid.geometry().CellCenter({col, row}));
      if (cell) EXPECT_EQ(cropped->at(*cell), grid.at({col, row}));
      else EXPECT_EQ(grid.at({col, row}), CellClass::kUnknown);
    }
  }
  EXPECT_EQ(cropped->Count(CellClass::kSlammable), 1u);
}

TEST(GridCrop, MarginStopsAtTheGridEdgeAndNothingObservedIsNothing) {
  ClassGrid grid(GridGeometry{.width = 10, .height = 10, .resolution_m = 0.05});
  EXPECT_FALSE(CropToObserved(grid).has_value());
  grid.Mark(CellIndex{0, 9}, CellClass::kFree);
  const auto cropped = CropToObserved(grid, 5);
  ASSERT_TRUE(cropped.has_value());
  EXPECT_EQ(cropped->geometry().width, 6);   // columns 0-5
  EXPECT_EQ(cropped->geometry().height, 6);  // rows 4-9
}

}  // namespace
}  // namespace flat2d::maps
