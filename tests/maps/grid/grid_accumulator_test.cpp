#include "maps/grid/grid_accumulator.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

GridGeometry Local() {
  return GridGeometry{.width = 40, .height = 40, .resolution_m = 0.1, .origin = Eigen::Vector2d(-2.0, -2.0)};
}

TEST(GridAccumulator, StructureSeenFromMovingPosesLandsInOnePlace) {
  const GridGeometry world = GeometryAround({{0.0, 0.0}, {1.0, 0.0}}, 3.0, 0.1);
  GridAccumulator accumulator(world);
  const Eigen::Vector2d post(1.55, 0.55);  // a pole in the world
  for (int k = 0; k < 10; ++k) {
    // The vehicle moves along x and turns; each revolution sees the pole in its own frame.
    const Eigen::Isometry2d world_T_grid = Eigen::Translation2d(0.1 * k, 0.0) * Eigen::Rotation2Dd(0.05 * k);
    ClassGrid grid(Local());
    grid.Mark(world_T_grid.inverse() * post, CellClass::kSlammable);
    grid.MarkLine(Eigen::Vector2d(0.0, 0.0), world_T_grid.inverse() * Eigen::Vector2d(1.5, 0.0), CellClass::kFree);
    accumulator.Add(grid, world_T_grid);
  }
  const ClassGrid result = accumulator.Result();
  EXPECT_EQ(accumulator.revolutions(), 10);
  EXPECT_EQ(result.at(*world.CellOf(post)), CellClass::kSlammable);
  EXPECT_EQ(result.Count(CellClass::kSlammable), 1u);
  EXPECT_EQ(result.at(*world.CellOf({1.0, 0.05})), CellClass::kFree);
}

TEST(GridAccumulator, StructureSeenRarelyIsOutvoted) {
  const GridGeometry world = GeometryAround({{0.0, 0.0}}, 2.0, 0.1);
  GridAccumulator accumulator(world);
  for (int k = 0; k < 10; ++k) {
    ClassGrid grid(Local());
    // A car parked for 2 of 10 revolutions at (1, 1); free ground there otherwise.
    grid.Mark(Eigen::Vector2d(1.05, 1.05), k < 2 ? CellClass::kSlammable : CellClass::kFree);
    // A wall seen every time, and a single false hit.
    grid.Mark(Eigen::Vector2d(-1.05, 1.05), CellClass::kSlammable);
    if (k == 5) grid.Mark(Eigen::Vector2d(0.55, -1.05), CellClass::kSlammable);
    accumulator.Add(grid, Eigen::Isometry2d::Identity());
  }
  const ClassGrid result = accumulator.Result();
  EXPECT_EQ(result.at(*world.CellOf({1.05, 1.05})), CellClass::kFree);
  EXPECT_EQ(result.at(*world.CellOf({-1.05, 1.05})), CellClass::kSlammable);
  EXPECT_EQ(result.at(*world.CellOf({0.55, -1.05})), CellClass::kFree);  // one vote < min_structure_votes
  EXPECT_EQ(result.at(*world.CellOf({0.0, 1.95})), CellClass::kUnknown);
}

TEST(GridAccumulator, GeometryAroundCoversThePosesAndTheMargin) {
  const GridGeometry g = GeometryAround({{-3.02, 1.0}, {10.0, -4.0}}, 5.0, 0.05);
  EXPECT_LE(g.origin.x(), -8.02);
  EXPECT_LE(g.origin.y(), -9.0);
  EXPECT_GE(g.origin.x() + g.width * g.resolution_m, 15.0);
  EXPECT_GE(g.origin.y() + g.height * g.resolution_m, 6.0);
  EXPECT_NEAR(std::remainder(g.origin.x(), 0.05), 0.0, 1e-9);
}

}  // namespace
}  // namespace flat2d::maps
