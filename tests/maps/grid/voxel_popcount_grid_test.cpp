#include "maps/grid/voxel_popcount_grid.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

GridGeometry TenMetres() {
  return GridGeometry{.width = 200, .height = 200, .resolution_m = 0.05,
                      .origin = Eigen::Vector2d(-5.0, -5.0)};
}

TEST(GridGeometry, CellOfAndCenterAgree) {
  const GridGeometry geometry = TenMetres();
  const auto cell = geometry.CellOf({0.12, -4.99});
  ASSERT_TRUE(cell);
  EXPECT_EQ(*cell, (CellIndex{102, 0}));
  EXPECT_TRUE(geometry.CellCenter(*cell).isApprox(Eigen::Vector2d(0.125, -4.975)));
  EXPECT_FALSE(geometry.CellOf({5.0, 0.0}));   // the far edge is outside
  EXPECT_FALSE(geometry.CellOf({-5.01, 0.0}));
  EXPECT_FALSE(geometry.CellOf({std::nan(""), 0.0}));
}

TEST(VoxelPopcountGrid, WallIsStructureGroundIsNot) {
  VoxelPopcountGrid grid(TenMetres(), 0.1f);
  for (float z = 0.0f; z <= 2.0f; z += 0.07f) grid.Add({2.02f, 1.0f, z});  // a wall's face
  for (int i = 0; i < 50; ++i) grid.Add({-1.0f, -1.0f, 0.01f * static_cast<float>(i % 3)});
  const auto wall = grid.geometry().CellOf({2.02, 1.0});
  const auto ground = grid.geometry().CellOf({-1.0, -1.0});
  ASSERT_TRUE(wall && ground);
  EXPECT_GE(grid.column(*wall).popcount(), 19);
  EXPECT_TRUE(grid.IsStructure(*wall, 5));
  EXPECT_FALSE(grid.IsStructure(*ground, 5));
  EXPECT_EQ(grid.column(*ground).popcount(), 1);
}

TEST(VoxelPopcountGrid, RejectsOutsideAndNonFinitePoints) {
  VoxelPopcountGrid grid(TenMetres(), 0.1f);
  EXPECT_FALSE(grid.Add({6.0f, 0.0f, 0.0f}));
  EXPECT_FALSE(grid.Add({0.0f, 0.0f, std::numeric_limits<float>::quiet_NaN()}));
  EXPECT_FALSE(grid.Add({std::numeric_limits<float>::infinity(), 0.0f, 0.0f}));
  for (const VoxelColumn& column : grid.columns()) EXPECT_TRUE(column.empty());
}

TEST(VoxelPopcountGrid, AddAndClearAllocateNothing) {
  VoxelPopcountGrid grid(TenMetres(), 0.1f);
  const auto before = testing::AllocationCount();
  for (int i = 0; i < 10000; ++i) {
    grid.Add({static_cast<float>(i % 97) * 0.1f - 4.8f, static_cast<float>(i % 89) * 0.1f - 4.4f,
              static_cast<float>(i % 31) * 0.07f});
  }
  grid.Clear();
  EXPECT_EQ(testing::AllocationCount(), before);
  for (const VoxelColumn& column : grid.columns()) ASSERT_TRUE(column.empty());
}

}  // namespace
}  // namespace flat2d::maps
