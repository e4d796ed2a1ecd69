#include "maps/grid/class_grid.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "maps/grid/hole_fill_in.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

GridGeometry Geometry() {
  return GridGeometry{.width = 100, .height = 80, .resolution_m = 0.1, .origin = Eigen::Vector2d(-5.0, -4.0)};
}

TEST(ClassGrid, MarkKeepsTheStrongestClass) {
  ClassGrid grid(Geometry());
  const Eigen::Vector2d p(1.03, 2.07);
  EXPECT_TRUE(grid.Mark(p, CellClass::kSlammable));
  EXPECT_TRUE(grid.Mark(p, CellClass::kFree));
  EXPECT_EQ(grid.at(*grid.geometry().CellOf(p)), CellClass::kSlammable);
  EXPECT_FALSE(grid.Mark(Eigen::Vector2d(100.0, 0.0), CellClass::kHazard));
  EXPECT_EQ(grid.Count(CellClass::kSlammable), 1u);
  EXPECT_EQ(grid.Count(CellClass::kUnknown), grid.geometry().cell_count() - 1);
}

// Every cell the segment passes through well inside (not just touching a corner) is marked,
// and no marked cell is farther than one cell diagonal from the segment.
TEST(ClassGrid, MarkLineCoversTheSegmentAndNothingElse) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-4.9, 4.9), y(-3.9, 3.9);
  for (int trial = 0; trial < 100; ++trial) {
    ClassGrid grid(Geometry());
    const Eigen::Vector2d a{x(rng), y(rng)}, b{x(rng), y(rng)};  // braces: drawn in order
    grid.MarkLine(a, b, CellClass::kHazard);
    EXPECT_EQ(grid.at(*grid.geometry().CellOf(a)), CellClass::kHazard);
    EXPECT_EQ(grid.at(*grid.geometry().CellOf(b)), CellClass::kHazard);
    const Eigen::Vector2d direction = (b - a).normalized();
    for (int row = 0; row < grid.geometry().height; ++row) {
      for (int col = 0; col < grid.geometry().width; ++col) {
        if (grid.at({col, row}) != CellClass::kHazard) continue;
        const Eigen::Vector2d c = grid.geometry().CellCenter({col, row}) - a;
        const double along = std::clamp(c.dot(direction), 0.0, (b - a).norm());
        EXPECT_LE((c - along * direction).norm(), 0.1 * std::sqrt(2.0)) << trial;
      }
    }
    // An 8-connected line marks one cell per step along its major axis, no more, no fewer.
    const CellIndex ca = *grid.geometry().CellOf(a), cb = *grid.geometry().CellOf(b);
    const auto steps = static_cast<std::size_t>(std::max(std::abs(cb.col - ca.col), std::abs(cb.row - ca.row)));
    EXPECT_EQ(grid.Count(CellClass::kHazard), steps + 1) << trial;
  }
}

TEST(ClassGrid, LinesFromFarOutsideAreClipped) {
  ClassGrid grid(Geometry());
  grid.MarkLine({-1e9, 0.05}, {1e9, 0.05}, CellClass::kFree);  // would be 2e10 cells unclipped
  EXPECT_EQ(grid.Count(CellClass::kFree), 100u);
  grid.MarkLine({-1e9, 100.0}, {1e9, 100.0}, CellClass::kHazard);  // misses the grid
  EXPECT_EQ(grid.Count(CellClass::kHazard), 0u);
  grid.MarkLine({std::nan(""), 0.0}, {1.0, 1.0}, CellClass::kHazard);
  EXPECT_EQ(grid.Count(CellClass::kHazard), 0u);
}

TEST(HoleFillIn, JoinsSameClassReturnsCloserThanTheBound) {
  ClassGrid grid(Geometry());
  const std::array<Eigen::Vector2d, 3> previous_xy{Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(3.0, 0.0),
                                                   Eigen::Vector2d(4.0, 0.0)};
  const std::array<Eigen::Vector2d, 3> current_xy{Eigen::Vector2d(2.0, 0.2), Eigen::Vector2d(3.0, 0.2),
                                                  Eigen::Vector2d(4.0, 0.6)};
  const std::array previous_class{CellClass::kSlammable, CellClass::kHazard, CellClass::kSlammable};
  const std::array current_class{CellClass::kSlammable, CellClass::kSlammable, CellClass::kSlammable};
  // Laser 0: same class, 0.2 m apart: joined. Laser 1: classes differ. Laser 2: 0.6 m apart.
  const int drawn = FillIn({previous_xy, previous_class}, {current_xy, current_class}, 0.25, grid);
  EXPECT_EQ(drawn, 1);
  EXPECT_EQ(grid.at(*grid.geometry().CellOf({2.0, 0.1})), CellClass::kSlammable);
  EXPECT_EQ(grid.at(*grid.geometry().CellOf({3.0, 0.1})), CellClass::kUnknown);
  EXPECT_EQ(grid.at(*grid.geometry().CellOf({4.0, 0.3})), CellClass::kUnknown);
  EXPECT_EQ(FillIn({previous_xy, previous_class}, {current_xy, current_class}, 0.7, grid), 2);
  EXPECT_EQ(grid.at(*grid.geometry().CellOf({4.0, 0.3})), CellClass::kSlammable);
}

TEST(HoleFillIn, FreeReturnsAreNotJoinedAndNothingAllocates) {
  ClassGrid grid(Geometry());
  const std::array<Eigen::Vector2d, 1> a{Eigen::Vector2d(1.0, 1.0)};
  const std::array<Eigen::Vector2d, 1> b{Eigen::Vector2d(1.0, 1.2)};
  const std::array free{CellClass::kFree};
  const auto before = testing::AllocationCount();
  EXPECT_EQ(FillIn({a, free}, {b, free}, 0.25, grid), 0);
  grid.MarkLine(a[0], b[0], CellClass::kHazard);
  EXPECT_EQ(testing::AllocationCount(), before);
}

}  // namespace
}  // namespace flat2d::maps
