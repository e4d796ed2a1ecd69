// Scan input: laser ranges, grid cells, decimation, rejection of bad points.
#include "localization/matching/scan_points.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::localization {
namespace {

TEST(ScanPointsTest, LaserRangesBecomePointsAndBadRangesAreDropped) {
  ScanPoints scan(10);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> ranges = {1.0F, 2.0F, nan, 50.0F, 0.01F};
  const double increment = 0.5 * std::numbers::pi;
  EXPECT_EQ(scan.AddLaserScan(ranges, -0.5 * std::numbers::pi, increment, 0.05, 30.0), 2u);
  ASSERT_EQ(scan.size(), 2u);
  EXPECT_NEAR(scan.points()[0].x(), 0.0, 1e-12);
  EXPECT_NEAR(scan.points()[0].y(), -1.0, 1e-12);
  EXPECT_NEAR(scan.points()[1].x(), 2.0, 1e-12);
  EXPECT_NEAR(scan.points()[1].y(), 0.0, 1e-12);
}

TEST(ScanPointsTest, RejectsNonFinitePointsAndOverflowWithACount) {
  ScanPoints scan(2);
  EXPECT_FALSE(scan.Add({std::nan(""), 0.0}));
  EXPECT_FALSE(scan.Add({0.0, std::numeric_limits<double>::infinity()}));
  EXPECT_TRUE(scan.Add({1.0, 1.0}));
  EXPECT_TRUE(scan.Add({2.0, 1.0}));
  EXPECT_FALSE(scan.Add({3.0, 1.0}));
  EXPECT_EQ(scan.size(), 2u);
  EXPECT_EQ(scan.rejected(), 3u);
}

TEST(ScanPointsTest, GridCellsBecomeCellCentres) {
  GridGeometry geometry;
  geometry.width = 4;
  geometry.height = 3;
  geometry.resolution = 0.5;
  geometry.origin = {-1.0, -0.75};
  MatchGrid grid(geometry);
  grid.SetOccupied(0, 0);
  grid.SetOccupied(3, 2);
  ScanPoints scan(8);
  EXPECT_EQ(scan.AddGridCells(grid), 2u);
  EXPECT_TRUE(scan.points()[0].isApprox(Eigen::Vector2d(-0.75, -0.5)));
  EXPECT_TRUE(scan.points()[1].isApprox(Eigen::Vector2d(0.75, 0.5)));
}

TEST(ScanPointsTest, VoxelDecimationKeepsOneCentroidPerVoxelWithoutAllocating) {
  constexpr std::uint32_t kSeed = 7;
  std::mt19937 random(kSeed);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  ScanPoints scan(4000);
  for (int i = 0; i < 4000; ++i) scan.Add({coordinate(random), coordinate(random)});
  // The expected centroids, by brute force over the 40 x 40 voxels of 0.1 m.
  std::vector<Eigen::Vector3d> sums(1600, Eigen::Vector3d::Zero());
  for (const Eigen::Vector2d& p : scan.points()) {
    const int ix = static_cast<int>(std::floor(p.x() / 0.1)) + 20;
    const int iy = static_cast<int>(std::floor(p.y() / 0.1)) + 20;
    sums[static_cast<std::size_t>(iy * 40 + ix)] += Eigen::Vector3d(p.x(), p.y(), 1.0);
  }
  std::size_t occupied = 0;
  for (const Eigen::Vector3d& s : sums) occupied += s.z() > 0.0 ? 1 : 0;

  const std::uint64_t before = flat2d::testing::AllocationCount();
  scan.VoxelDecimate(0.1);
  EXPECT_EQ(flat2d::testing::AllocationCount(), before);
  ASSERT_EQ(scan.size(), occupied) << "seed " << kSeed;
  for (const Eigen::Vector2d& p : scan.points()) {
    const int ix = static_cast<int>(std::floor(p.x() / 0.1)) + 20;
    const int iy = static_cast<int>(std::floor(p.y() / 0.1)) + 20;
    const Eigen::Vector3d& s = sums[static_cast<std::size_t>(iy * 40 + ix)];
    ASSERT_GT(s.z(), 0.0);
    EXPECT_NEAR(p.x(), s.x() / s.z(), 1e-12);
    EXPECT_NEAR(p.y(), s.y() / s.z(), 1e-12);
  }
}

}  // namespace
}  // namespace flat2d::localization

namespace flat2d::localization {
namespace {

TEST(MatchGridTest, ResetClearsAndMovesWithoutChangingTheSize) {
  GridGeometry geometry;
  geometry.width = 40;
  geometry.height = 30;
  geometry.resolution = 0.05;
  MatchGrid grid(geometry);
  grid.SetOccupied(3, 4);
  ASSERT_TRUE(grid.MarkPoint({1.0, 1.0}));
  ASSERT_EQ(grid.OccupiedCount(), 2u);
  grid.Reset({10.0, -5.0});
  EXPECT_EQ(grid.OccupiedCount(), 0u);
  EXPECT_EQ(grid.width(), 40);
  EXPECT_EQ(grid.geometry().origin, Eigen::Vector2d(10.0, -5.0));
  EXPECT_FALSE(grid.MarkPoint({1.0, 1.0}));  // now outside
  EXPECT_TRUE(grid.MarkPoint({10.52, -4.98}));
  EXPECT_TRUE(grid.Occupied(10, 0));
}

}  // namespace
}  // namespace flat2d::localization
