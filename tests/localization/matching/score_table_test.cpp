// The score table (the blurred map) and the pyramid's upper-bound property.
#include "localization/matching/score_table.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "localization/matching/match_grid.hpp"
#include "localization/matching/score_pyramid.hpp"

namespace flat2d::localization {
namespace {

GridGeometry Geometry(int width, int height) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = height;
  geometry.resolution = 0.05;
  geometry.origin = {-1.0, 2.0};
  return geometry;
}

TEST(MatchGridTest, CellsOfPointsAndClassCells) {
  const GridGeometry geometry = Geometry(40, 30);
  EXPECT_EQ(geometry.CellOf({-1.0, 2.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(geometry.CellOf({-0.951, 2.049}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(geometry.CellOf({-0.949, 2.051}), Eigen::Vector2i(1, 1));
  EXPECT_EQ(geometry.CellOf({-1.001, 2.0}), Eigen::Vector2i(-1, 0));
  EXPECT_EQ(geometry.CellOf({1e300, -1e300}).x(), 1000000000);

  std::vector<std::uint8_t> classes(geometry.CellCount(), 0);
  classes[5 * 40 + 7] = 3;
  classes[6 * 40 + 7] = 2;
  Result<MatchGrid> grid = MatchGrid::FromClassCells(geometry, classes, 3);
  ASSERT_TRUE(grid.ok());
  EXPECT_TRUE(grid->Occupied(7, 5));
  EXPECT_FALSE(grid->Occupied(7, 6));
  EXPECT_EQ(grid->OccupiedCount(), 1u);
  EXPECT_FALSE(grid->Occupied(-1, 0));

  classes.pop_back();
  EXPECT_FALSE(MatchGrid::FromClassCells(geometry, classes, 3).ok());
  GridGeometry bad = geometry;
  bad.resolution = std::nan("");
  EXPECT_FALSE(MatchGrid::FromPoints(bad, {}).ok());
}

TEST(ScoreTableTest, GaussianOfTheDistanceToTheNearestStructure) {
  MatchGrid grid(Geometry(40, 30));
  grid.SetOccupied(10, 10);
  grid.SetOccupied(30, 20);
  ScoreTableOptions options;
  options.sigma_cells = 1.5;
  ScoreTable table(40 * 30, options);
  ASSERT_TRUE(table.Rebuild(grid).ok());
  const int radius = static_cast<int>(std::floor(options.radius_sigmas * options.sigma_cells));
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const int d2 = std::min((x - 10) * (x - 10) + (y - 10) * (y - 10),
                              (x - 30) * (x - 30) + (y - 20) * (y - 20));
      const int expected =
          d2 > radius * radius ? 0 : static_cast<int>(std::lround(255.0 * std::exp(-d2 / 4.5)));
      ASSERT_EQ(table.At(x, y), expected) << "cell " << x << ", " << y;
    }
  }
  EXPECT_EQ(table.At(-1, 10), 0);
  EXPECT_EQ(table.At(10, 30), 0);
  // Bilinear lookups are exact at cell centres and in between elsewhere.
  EXPECT_DOUBLE_EQ(table.Interpolate(10.5, 10.5), 255.0);
  EXPECT_DOUBLE_EQ(table.Interpolate(11.0, 10.5), 0.5 * (255.0 + table.At(11, 10)));

  ScoreTable small(100, options);
  EXPECT_FALSE(small.Rebuild(grid).ok());
}

TEST(ScorePyramidTest, EveryLevelBoundsItsBlockExactly) {
  std::mt19937 random(42);
  MatchGrid grid(Geometry(37, 23));
  std::uniform_int_distribution<int> x(0, 36);
  std::uniform_int_distribution<int> y(0, 22);
  for (int i = 0; i < 12; ++i) {
    const int column = x(random);  // drawn before the row: a call's arguments have no order
    grid.SetOccupied(column, y(random));
  }
  ScoreTable table(37 * 23);
  ASSERT_TRUE(table.Rebuild(grid).ok());
  ScorePyramid pyramid(37 * 23, 6);
  ASSERT_TRUE(pyramid.Rebuild(table).ok());
  for (int level = 1; level < 6; ++level) {
    const int block = 1 << level;
    for (int y0 = -block - 2; y0 < 26; ++y0) {
      for (int x0 = -block - 2; x0 < 40; ++x0) {
        int block_max = 0;
        for (int dy = 0; dy < block; ++dy) {
          for (int dx = 0; dx < block; ++dx) block_max = std::max(block_max, table.At(x0 + dx, y0 + dy));
        }
        const int bound = pyramid.Bound(level, x0, y0);
        ASSERT_GE(bound, block_max) << "level " << level << " at " << x0 << ", " << y0;
        // Inside the map the bound is the block's maximum itself.
        if (x0 >= 0 && y0 >= 0) {
          ASSERT_EQ(bound, block_max);
        }
      }
    }
  }
}

}  // namespace
}  // namespace flat2d::localization
