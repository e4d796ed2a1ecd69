#include "maps/grid/voxel_column.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

constexpr float kBand = 0.1f;

TEST(VoxelColumn, FirstReturnSetsZMinAndBandZero) {
  VoxelColumn column;
  EXPECT_TRUE(column.empty());
  AddHeight(column, 1.25f, kBand);
  EXPECT_FLOAT_EQ(column.z_min, 1.25f);
  EXPECT_EQ(column.bands, 1u);
}

TEST(VoxelColumn, HigherReturnsSetTheirBand) {
  VoxelColumn column;
  AddHeight(column, 0.0f, kBand);
  AddHeight(column, 0.35f, kBand);  // band 3
  AddHeight(column, 0.99f, kBand);  // band 9
  EXPECT_EQ(column.bands, (1u << 0) | (1u << 3) | (1u << 9));
  EXPECT_EQ(column.popcount(), 3);
}

TEST(VoxelColumn, LowerReturnShiftsByWholeBandsKeepingAlignment) {
  VoxelColumn column;
  AddHeight(column, 1.0f, kBand);
  AddHeight(column, 1.15f, kBand);  // band 1
  AddHeight(column, 0.78f, kBand);  // 0.22 below: shift ceil(2.2) = 3 bands
  EXPECT_NEAR(column.z_min, 0.7f, 1e-6);
  // Old bands 0 and 1 are now 3 and 4; the new return is in [0.7, 0.8): band 0.
  EXPECT_EQ(column.bands, (1u << 0) | (1u << 3) | (1u << 4));
}

TEST(VoxelColumn, BandsPushedPastTheTopFallOff) {
  VoxelColumn column;
  AddHeight(column, 0.0f, kBand);
  AddHeight(column, 6.35f, kBand);  // band 63
  AddHeight(column, -0.05f, kBand);  // shift by 1: band 63 falls off, band 0 becomes 1
  EXPECT_EQ(column.bands, (1ull << 0) | (1ull << 1));
  AddHeight(column, -100.0f, kBand);  // far below: every earlier band falls off
  EXPECT_EQ(column.bands, 1u);
  EXPECT_NEAR(column.z_min, -100.0f, kBand);
  EXPECT_LE(column.z_min, -100.0f);
}

TEST(VoxelColumn, ReturnsAboveTheTopAreDropped) {
  VoxelColumn column;
  AddHeight(column, 0.0f, kBand);
  AddHeight(column, 6.45f, kBand);  // band 64
  EXPECT_EQ(column.bands, 1u);
}

// Order of arrival must not matter for the bands a set of returns occupies, as long as the
// lowest return decides z-min: compare against bands computed directly from the minimum.
TEST(VoxelColumn, ResultIsIndependentOfArrivalOrderUpToBandAlignment) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> height(0.0f, 3.0f);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> heights(20);
    for (float& h : heights) h = height(rng);
    VoxelColumn column;
    for (float h : heights) AddHeight(column, h, kBand);
    // Every return lies in a set band and every set band holds a return.
    std::uint64_t expected = 0;
    for (float h : heights) {
      const int band = static_cast<int>(std::floor((h - column.z_min) / kBand + 1e-4f));
      ASSERT_GE(band, 0);
      if (band < kVoxelBands) expected |= 1ull << band;
    }
    EXPECT_EQ(column.bands, expected) << "trial " << trial;
    EXPECT_LE(column.z_min, *std::min_element(heights.begin(), heights.end()) + 1e-5f);
  }
}

TEST(VoxelColumn, BandMaskSelectsHeightsAboveZMin) {
  EXPECT_EQ(BandMask(0.0f, 0.3f, kBand), 0b111u);
  EXPECT_EQ(BandMask(0.2f, 0.5f, kBand), 0b11100u);
  EXPECT_EQ(BandMask(0.25f, 0.31f, kBand), 0b1100u);  // partial bands are included
  EXPECT_EQ(BandMask(0.0f, 100.0f, kBand), ~0ull);
  EXPECT_EQ(BandMask(7.0f, 8.0f, kBand), 0u);
  EXPECT_EQ(BandMask(0.5f, 0.5f, kBand), 0u);
}

TEST(VoxelColumn, BandMaskIsolatesObstaclesAtVehicleHeight) {
  VoxelColumn overhang;  // ground return plus a branch at 2.5 m
  AddHeight(overhang, 0.0f, kBand);
  AddHeight(overhang, 2.55f, kBand);
  VoxelColumn wall;
  for (float z = 0.0f; z < 3.0f; z += 0.05f) AddHeight(wall, z, kBand);
  const std::uint64_t vehicle = BandMask(0.2f, 1.8f, kBand);
  EXPECT_EQ(std::popcount(overhang.bands & vehicle), 0);
  EXPECT_EQ(std::popcount(wall.bands & vehicle), 16);
}

}  // namespace
}  // namespace flat2d::maps
