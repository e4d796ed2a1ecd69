#include "maps/grid/polar_voxel_grid.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

constexpr double kPi = std::numbers::pi;

PolarGridLayout Layout() { return {.azimuth_bins = 360, .range_bins = 400, .range_resolution_m = 0.1}; }

int AzimuthBinOf(const PolarVoxelGrid& grid, const Eigen::Vector2d& point) {
  // Search the bin whose centre is nearest: independent of Add's arithmetic.
  int best = -1;
  double best_distance = 1e9;
  for (int a = 0; a < grid.layout().azimuth_bins; ++a) {
    const int r = static_cast<int>(point.norm() / grid.layout().range_resolution_m);
    const double distance = (grid.BinCenter({a, r}) - point).norm();
    if (distance < best_distance) best_distance = distance, best = a;
  }
  return best;
}

TEST(PolarVoxelGrid, BinsByAzimuthAndRange) {
  PolarVoxelGrid grid(Layout(), 0.1f);
  const Eigen::Vector3f pole(-3.0f, 4.0f, 0.0f);  // range 5 m, azimuth 126.87 deg
  for (float z = 0.0f; z < 1.5f; z += 0.1f) ASSERT_TRUE(grid.Add({pole.x(), pole.y(), z}));
  const PolarBin bin{AzimuthBinOf(grid, pole.head<2>().cast<double>()), 50};
  EXPECT_EQ(bin.azimuth, 126);
  EXPECT_TRUE(grid.IsStructure(bin, 10));
  EXPECT_LT((grid.BinCenter(bin) - Eigen::Vector2d(-3.0, 4.0)).norm(), 0.1);
}

TEST(PolarVoxelGrid, NegativeAndWrappedAzimuthsLandInTheSameBin) {
  PolarVoxelGrid a(Layout(), 0.1f);
  PolarVoxelGrid b(Layout(), 0.1f);
  a.Add(-kPi / 2.0 + 0.001, 3.05, 0.0f);
  b.Add(3.0 * kPi / 2.0 + 0.001, 3.05, 0.0f);
  EXPECT_TRUE(a.column({270, 30}).bands == 1u);
  EXPECT_TRUE(b.column({270, 30}).bands == 1u);
}

TEST(PolarVoxelGrid, RejectsReturnsBeyondRangeOrNotFinite) {
  PolarVoxelGrid grid(Layout(), 0.1f);
  EXPECT_FALSE(grid.Add(0.0, 40.0, 0.0f));  // 400 bins x 0.1 m: 40 m is the first one out
  EXPECT_TRUE(grid.Add(0.0, 39.99, 0.0f));
  EXPECT_FALSE(grid.Add(std::nan(""), 1.0, 0.0f));
  EXPECT_FALSE(grid.Add(0.0, 1.0, std::nanf("")));
}

TEST(PolarVoxelGrid, AddAndClearAllocateNothing) {
  PolarVoxelGrid grid(Layout(), 0.1f);
  const auto before = testing::AllocationCount();
  for (int i = 0; i < 10000; ++i) {
    grid.Add({std::cos(0.01f * static_cast<float>(i)) * 10.0f,
              std::sin(0.01f * static_cast<float>(i)) * 10.0f, static_cast<float>(i % 20) * 0.1f});
  }
  grid.Clear();
  EXPECT_EQ(testing::AllocationCount(), before);
}

}  // namespace
}  // namespace flat2d::maps
