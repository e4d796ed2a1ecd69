#include "maps/range3d/projection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps::range3d {
namespace {

constexpr float kDegToRad = 3.14159265358979F / 180.0F;

TEST(RangeProjection, PinholeRoundTripsEveryPixel) {
  const RangeProjection projection = RangeProjection::Pinhole({});
  for (int row = 0; row < projection.rows(); row += 7) {
    for (int col = 0; col < projection.cols(); col += 5) {
      const float depth = 0.5F + 0.01F * static_cast<float>(row + col);
      const Pixel pixel = projection.Project(projection.Unproject(row, col, depth));
      ASSERT_TRUE(pixel.valid());
      EXPECT_EQ(pixel.row, row);
      EXPECT_EQ(pixel.col, col);
      EXPECT_NEAR(pixel.depth, depth, 1e-5F);
    }
  }
}

TEST(RangeProjection, PinholeMatchesEq311) {
  // (u - cx) d / f with the TUM default intrinsics: pixel (0, 0) at 2 m.
  const RangeProjection projection = RangeProjection::Pinhole({});
  const Eigen::Vector3f p = projection.Unproject(0, 0, 2.0F);
  EXPECT_NEAR(p.x(), -319.5F * 2.0F / 525.0F, 1e-5F);
  EXPECT_NEAR(p.y(), -239.5F * 2.0F / 525.0F, 1e-5F);
  EXPECT_FALSE(projection.Project({0.0F, 0.0F, -1.0F}).valid());   // behind the camera
  EXPECT_FALSE(projection.Project({10.0F, 0.0F, 1.0F}).valid());   // outside the image
}

// HDL-32E: elevations -30.67 .. +10.67 deg in steps of 4/3 (user manual table).
SphericalLayout Hdl32Layout() {
  SphericalLayout layout;
  layout.cols = 2160;
  for (int row = 0; row < 32; ++row) layout.row_elevation_rad.push_back((10.67F - 1.3333F * static_cast<float>(row)) * kDegToRad);
  return layout;
}

TEST(RangeProjection, SphericalFindsTheLaserByElevation) {
  const RangeProjection projection = RangeProjection::Spherical(Hdl32Layout());
  ASSERT_EQ(projection.rows(), 32);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> azimuth(-3.14F, 3.14F), jitter(-0.6F, 0.6F), range(1.0F, 80.0F);
  for (int trial = 0; trial < 2000; ++trial) {
    const int laser = trial % 32;
    const float elevation = (10.67F - 1.3333F * static_cast<float>(laser) + jitter(rng)) * kDegToRad;
    const float a = azimuth(rng), r = range(rng);
    const Eigen::Vector3f p(r * std::cos(elevation) * std::cos(a), r * std::cos(elevation) * std::sin(a), r * std::sin(elevation));
    const Pixel pixel = projection.Project(p);
    ASSERT_TRUE(pixel.valid()) << "trial " << trial;
    EXPECT_EQ(pixel.row, laser) << "trial " << trial;
    EXPECT_NEAR(pixel.depth, r, 1e-3F * r);
    EXPECT_NEAR(static_cast<float>(pixel.col), (a + 3.14159265F) / (2.0F * 3.14159265F) * 2160.0F, 1.01F);
  }
  // Beyond half a gap above the top laser or below the bottom one: no row.
  EXPECT_FALSE(projection.Project({std::cos(12.0F * kDegToRad), 0.0F, std::sin(12.0F * kDegToRad)}).valid());
  EXPECT_FALSE(projection.Project({std::cos(-32.0F * kDegToRad), 0.0F, std::sin(-32.0F * kDegToRad)}).valid());
}

TEST(RangeProjection, SphericalRoundTripsPixelCentres) {
  const RangeProjection projection = RangeProjection::Spherical(Hdl32Layout());
  for (int row = 0; row < 32; ++row) {
    for (int col = 0; col < 2160; col += 37) {
      const Pixel pixel = projection.Project(projection.Unproject(row, col, 12.5F));
      ASSERT_TRUE(pixel.valid());
      EXPECT_EQ(pixel.row, row);
      EXPECT_EQ(pixel.col, col);
      EXPECT_NEAR(pixel.depth, 12.5F, 1e-4F);
    }
  }
}

// The HDL-32E layout with each row's column shifted: fractions of a column, one of them
// negative, as firing-aligned columns have (range_frame.hpp, LidarProjection).
SphericalLayout ShiftedHdl32Layout() {
  SphericalLayout layout = Hdl32Layout();
  for (int row = 0; row < 32; ++row) layout.row_column_shift.push_back(0.03F * static_cast<float>(row) - 0.095F);
  return layout;
}

// The batch projection must give the pixels of Project one at a time, including for points
// above and below the lasers, at the origin, on the axes (atan2's folds) and NaN points.
void ExpectBatchEqualsOneAtATime(const RangeProjection& projection) {
  const unsigned seed = 7;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-60.0F, 60.0F);
  std::vector<Eigen::Vector3f> points;
  for (int k = 0; k < 3000; ++k) {  // braces: x, y and z drawn in order
    points.push_back(Eigen::Vector3f{coordinate(rng), coordinate(rng), 0.2F * coordinate(rng)});
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const Eigen::Vector3f& p : {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(5, 0, 0), Eigen::Vector3f(-5, 0, 0),
                                  Eigen::Vector3f(0, 5, 0), Eigen::Vector3f(0, -5, 0), Eigen::Vector3f(-5, -0.0F, 0.1F),
                                  Eigen::Vector3f(-5, 0.001F, 0.1F), Eigen::Vector3f(3, 3, 0), Eigen::Vector3f(0, 0, 5),
                                  Eigen::Vector3f(nan, 1, 1), Eigen::Vector3f(1, nan, 1), Eigen::Vector3f(1, 1, nan)}) {
    points.push_back(p);
  }
  for (std::size_t begin = 0; begin < points.size(); begin += RangeProjection::kMaxBatch) {
    const std::size_t count = std::min(RangeProjection::kMaxBatch, points.size() - begin);
    std::vector<float> x, y, z;
    for (std::size_t i = begin; i < begin + count; ++i) {
      x.push_back(points[i].x()), y.push_back(points[i].y()), z.push_back(points[i].z());
    }
    std::vector<std::int32_t> offset(count);
    std::vector<float> depth(count);
    projection.ProjectSpherical(x.data(), y.data(), z.data(), count, offset.data(), depth.data());
    for (std::size_t i = 0; i < count; ++i) {
      const Pixel one = projection.Project(points[begin + i]);
      const std::int32_t expected = one.valid() ? one.row * projection.cols() + one.col : -1;
      ASSERT_EQ(offset[i], expected) << "seed " << seed << ", point " << points[begin + i].transpose();
      if (one.valid()) {
        EXPECT_EQ(depth[i], one.depth);
        EXPECT_GE(one.col, 0);
        EXPECT_LT(one.col, projection.cols());
      }
    }
  }
}

TEST(RangeProjection, SphericalBatchEqualsOneAtATime) {
  ExpectBatchEqualsOneAtATime(RangeProjection::Spherical(Hdl32Layout()));
  ExpectBatchEqualsOneAtATime(RangeProjection::Spherical(ShiftedHdl32Layout()));
}

TEST(RangeProjection, ShiftedRowsMoveTheirColumns) {
  const RangeProjection shifted = RangeProjection::Spherical(ShiftedHdl32Layout());
  const RangeProjection plain = RangeProjection::Spherical(Hdl32Layout());
  int moved = 0;
  for (int row = 0; row < 32; ++row) {
    const float shift = 0.03F * static_cast<float>(row) - 0.095F;
    for (int col = 0; col < 2160; col += 37) {
      // Pixel centres round-trip; a point in the middle of an unshifted column moves to the
      // next column exactly when its shift (never within 0.005 of a half) carries it over.
      const Pixel centre = shifted.Project(shifted.Unproject(row, col, 12.5F));
      ASSERT_TRUE(centre.valid());
      EXPECT_EQ(centre.row, row);
      EXPECT_EQ(centre.col, col);
      const Eigen::Vector3f mid_column = plain.Unproject(row, col, 12.5F);
      const int expected = static_cast<int>(std::floor(static_cast<float>(col) + 0.5F + shift) + 2160) % 2160;
      EXPECT_EQ(shifted.Project(mid_column).col, expected) << "row " << row << " col " << col;
      moved += expected != col ? 1 : 0;
    }
  }
  EXPECT_GT(moved, 0);
}

// A pyramid level of a spherical view: same rows, and every point in column c of the full
// view lands in column c / scale of the level, shifts included.
TEST(RangeProjection, CoarserColumnsHoldTheFullColumnsInBlocks) {
  const RangeProjection full = RangeProjection::Spherical(ShiftedHdl32Layout());
  std::mt19937 random(3);
  std::uniform_real_distribution<float> azimuth(-3.14159F, 3.14159F), elevation(-30.0F * kDegToRad, 10.0F * kDegToRad);
  for (const int scale : {2, 4, 8}) {
    const RangeProjection level = full.ColumnsDividedBy(scale);
    ASSERT_EQ(level.rows(), full.rows());
    ASSERT_EQ(level.cols(), full.cols() / scale);
    int compared = 0;
    for (int i = 0; i < 20000; ++i) {
      const float a = azimuth(random), e = elevation(random);
      const Eigen::Vector3f p(20.0F * std::cos(e) * std::cos(a), 20.0F * std::cos(e) * std::sin(a), 20.0F * std::sin(e));
      const Pixel fine = full.Project(p), coarse = level.Project(p);
      ASSERT_EQ(fine.valid(), coarse.valid());
      if (!fine.valid()) continue;
      // Left out: points within FastAtan2's error (7e-4 of a column) of a block border, where
      // the two images' float arithmetic may round to either side.
      const double column = (static_cast<double>(a) + 3.14159265358979) * 2160.0 / (2.0 * 3.14159265358979) +
                            (0.03 * fine.row - 0.095);
      const double into_block = std::fmod(column + 2160.0, static_cast<double>(scale));
      if (into_block < 2e-3 || into_block > scale - 2e-3) continue;
      EXPECT_EQ(coarse.row, fine.row);
      EXPECT_EQ(coarse.col, fine.col / scale) << "scale " << scale << " full column " << fine.col;
      ++compared;
    }
    EXPECT_GT(compared, 10000);
  }
  EXPECT_EQ(full.ColumnsDividedBy(7).rows(), 0);  // 2160 is not a multiple of 7
  EXPECT_EQ(full.ColumnsDividedBy(0).rows(), 0);
  EXPECT_EQ(RangeProjection::Pinhole(PinholeIntrinsics{}).ColumnsDividedBy(2).rows(), 0);
}

TEST(RangeProjection, SphericalRejectsAnUnsortedTable) {
  SphericalLayout layout = Hdl32Layout();
  std::swap(layout.row_elevation_rad[3], layout.row_elevation_rad[4]);
  EXPECT_EQ(RangeProjection::Spherical(layout).rows(), 0);
  EXPECT_EQ(RangeProjection::Spherical(SphericalLayout{}).rows(), 0);
  SphericalLayout short_shifts = Hdl32Layout();
  short_shifts.row_column_shift.assign(31, 0.0F);  // one row short
  EXPECT_EQ(RangeProjection::Spherical(short_shifts).rows(), 0);
}

TEST(RangeProjection, BinnedRowsSpanTheElevationRange) {
  const RangeProjection projection = RangeProjection::SphericalBinned(2048, 64, -25.0F * kDegToRad, 3.0F * kDegToRad);
  ASSERT_EQ(projection.rows(), 64);
  EXPECT_EQ(projection.Project({1.0F, 0.0F, std::tan(2.9F * kDegToRad)}).row, 0);
  EXPECT_EQ(projection.Project({1.0F, 0.0F, std::tan(-24.9F * kDegToRad)}).row, 63);
}

}  // namespace
}  // namespace flat2d::maps::range3d
