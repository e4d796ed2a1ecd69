#include "localization/peers/structure_scan.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "maps/grid/class_grid.hpp"

namespace flat2d::localization::peers {
namespace {

maps::ClassGrid EmptyGrid() {
  maps::GridGeometry geometry;
  geometry.width = 400;
  geometry.height = 400;
  geometry.resolution_m = 0.05;
  geometry.origin = Eigen::Vector2d(-10.0, -10.0);  // the vehicle at the centre
  return maps::ClassGrid(geometry);
}

int RayAt(double bearing, int rays) {
  return static_cast<int>(std::lround((bearing + std::numbers::pi) / (2.0 * std::numbers::pi / (rays - 1))));
}

TEST(StructureScan, RaysCoverTheTurnAsMrptLaysThemOut) {
  EXPECT_DOUBLE_EQ(RayBearing(0, 720), -std::numbers::pi);
  EXPECT_DOUBLE_EQ(RayBearing(719, 720), std::numbers::pi);
  EXPECT_NEAR(RayBearing(RayAt(0.0, 720), 720), 0.0, std::numbers::pi / 719);
}

TEST(StructureScan, NearestSlammableCellPerBearing) {
  maps::ClassGrid grid = EmptyGrid();
  // A wall 5 m ahead (x = 5) and another behind it at 8 m; only the nearer one returns.
  grid.MarkLine({5.0, -1.0}, {5.0, 1.0}, maps::CellClass::kSlammable);
  grid.MarkLine({8.0, -1.0}, {8.0, 1.0}, maps::CellClass::kSlammable);
  // A hazard 3 m to the left is not structure: no return.
  grid.MarkLine({-1.0, 3.0}, {1.0, 3.0}, maps::CellClass::kHazard);
  mrpt::obs::CObservation2DRangeScan scan;
  const int returns = StructureScan(grid, {.rays = 720}, scan);

  ASSERT_EQ(scan.getScanSize(), 720u);
  EXPECT_FLOAT_EQ(scan.aperture, static_cast<float>(2.0 * std::numbers::pi));
  const auto ahead = static_cast<std::size_t>(RayAt(0.0, 720));
  ASSERT_TRUE(scan.getScanRangeValidity(ahead));
  EXPECT_NEAR(scan.getScanRange(ahead), 5.025, 0.03);  // the cell centre
  const auto left = static_cast<std::size_t>(RayAt(std::numbers::pi / 2, 720));
  EXPECT_FALSE(scan.getScanRangeValidity(left));
  // The 2 m wall at 5 m spans atan(1/5) either side: about 45 rays of 0.5 degree.
  EXPECT_GT(returns, 40);
  EXPECT_LT(returns, 50);
}

TEST(StructureScan, IgnoresTheVehicleBodyAndBeyondMaxRange) {
  maps::ClassGrid grid = EmptyGrid();
  grid.Mark(Eigen::Vector2d(0.5, 0.0), maps::CellClass::kSlammable);   // inside min range
  grid.Mark(Eigen::Vector2d(0.0, -9.5), maps::CellClass::kSlammable);  // beyond 9 m
  StructureScanOptions options{.rays = 720};
  options.max_range_m = 9.0f;
  mrpt::obs::CObservation2DRangeScan scan;
  EXPECT_EQ(StructureScan(grid, options, scan), 0);
  // A scan reused for the next revolution starts clean.
  grid.Mark(Eigen::Vector2d(0.0, -4.0), maps::CellClass::kSlammable);
  EXPECT_EQ(StructureScan(grid, options, scan), 1);
  EXPECT_TRUE(scan.getScanRangeValidity(static_cast<std::size_t>(RayAt(-std::numbers::pi / 2, 720))));
}

}  // namespace
}  // namespace flat2d::localization::peers
