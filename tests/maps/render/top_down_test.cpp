#include "maps/render/top_down.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

// Defaults, but nothing drawn except points, so a pixel is either a point or background.
TopDownOptions PointsOnly() {
  TopDownOptions options;
  options.ring_spacing_m = 0;
  options.origin_marker_radius_px = 0;
  return options;
}

// Pixels that differ from the background, as (col, row).
std::vector<std::pair<int, int>> PaintedPixels(const RgbImage& image, Rgb background) {
  std::vector<std::pair<int, int>> painted;
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      if (image.At(col, row) != background) painted.emplace_back(col, row);
    }
  }
  return painted;
}

TEST(TopDownTest, ImageIsOddSquareCentredOnTheSensor) {
  const auto render = RenderTopDown({}, TopDownOptions{});
  ASSERT_TRUE(render.ok()) << render.error().message;
  EXPECT_EQ(render->image.width, 1001);
  EXPECT_EQ(render->image.height, 1001);
  // Default origin marker: a cross on the centre pixel.
  EXPECT_EQ(render->image.At(500, 500), (Rgb{255, 255, 255}));
  EXPECT_EQ(render->image.At(503, 500), (Rgb{255, 255, 255}));
  EXPECT_EQ(render->image.At(500, 497), (Rgb{255, 255, 255}));
}

TEST(TopDownTest, ForwardIsUpAndLeftIsLeft) {
  const TopDownOptions options = PointsOnly();
  const std::vector<TopDownPoint> forward = {{10.0f, 0.0f, 1.0f, 0.0f}};
  const std::vector<TopDownPoint> left = {{0.0f, 10.0f, 1.0f, 0.0f}};
  const auto up_render = RenderTopDown(forward, options);
  const auto left_render = RenderTopDown(left, options);
  ASSERT_TRUE(up_render.ok() && left_render.ok());

  // 10 m at 0.1 m/px is 100 px from the centre pixel (500, 500).
  using Pixels = std::vector<std::pair<int, int>>;
  EXPECT_EQ(PaintedPixels(up_render->image, options.background), (Pixels{{500, 400}}));
  EXPECT_EQ(PaintedPixels(left_render->image, options.background), (Pixels{{400, 500}}));
  // z = 1 on the default -3..5 m ramp is t = 0.5.
  EXPECT_EQ(up_render->image.At(500, 400), Viridis(0.5));
  EXPECT_EQ(up_render->drawn, 1u);
}

TEST(TopDownTest, RandomPointsLandOnTheirNearestPixel) {
  const unsigned seed = 42;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-49.0f, 49.0f);
  TopDownOptions options = PointsOnly();
  options.metres_per_pixel = 0.25;
  for (int trial = 0; trial < 50; ++trial) {
    const TopDownPoint point{coordinate(rng), coordinate(rng), 0.0f, 0.0f};
    const auto render = RenderTopDown(std::span(&point, 1), options);
    ASSERT_TRUE(render.ok());
    const int centre = render->image.width / 2;
    const int expected_row = centre - static_cast<int>(std::lround(point.x / 0.25f));
    const int expected_col = centre - static_cast<int>(std::lround(point.y / 0.25f));
    const auto painted = PaintedPixels(render->image, options.background);
    ASSERT_EQ(painted.size(), 1u) << "seed " << seed << " trial " << trial;
    EXPECT_EQ(painted[0], std::pair(expected_col, expected_row))
        << "seed " << seed << " trial " << trial << " x " << point.x << " y " << point.y;
  }
}

TEST(TopDownTest, OutOfExtentAndNonFinitePointsAreCountedAndSkipped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<TopDownPoint> points = {
      {0.0f, 0.0f, 0.0f, 0.0f},   {50.0f, -50.0f, 0.0f, 0.0f},  // inside (corner)
      {50.1f, 0.0f, 0.0f, 0.0f},  {0.0f, -60.0f, 0.0f, 0.0f},   // outside
      {1e30f, 1e30f, 0.0f, 0.0f}, {nan, 0.0f, 0.0f, 0.0f},      // huge, NaN
      {0.0f, inf, 0.0f, 0.0f},    {1.0f, 1.0f, nan, 0.0f}};
  const auto render = RenderTopDown(points, PointsOnly());
  ASSERT_TRUE(render.ok());
  EXPECT_EQ(render->drawn, 2u);
  EXPECT_EQ(render->outside_extent, 3u);
  EXPECT_EQ(render->non_finite, 3u);
  EXPECT_EQ(PaintedPixels(render->image, Rgb{}).size(), 2u);
}

TEST(TopDownTest, HighestPointWinsAPixelWhateverTheOrder) {
  const std::vector<TopDownPoint> low_first = {{5.0f, 5.0f, -3.0f, 0.0f}, {5.0f, 5.0f, 5.0f, 0.0f}};
  const std::vector<TopDownPoint> high_first = {low_first[1], low_first[0]};
  const auto a = RenderTopDown(low_first, PointsOnly());
  const auto b = RenderTopDown(high_first, PointsOnly());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->image.At(450, 450), Viridis(1.0));
  EXPECT_EQ(a->image.pixels, b->image.pixels);
}

TEST(TopDownTest, IntensityColouringUsesTheIntensityRange) {
  TopDownOptions options = PointsOnly();
  options.colour_by = TopDownColour::kIntensity;
  const std::vector<TopDownPoint> points = {{1.0f, 0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f, 255.0f}};
  const auto render = RenderTopDown(points, options);
  ASSERT_TRUE(render.ok());
  EXPECT_EQ(render->image.At(500, 490), Viridis(0.0));
  EXPECT_EQ(render->image.At(500, 480), Viridis(1.0));
}

TEST(TopDownTest, RangeRingsSitEveryTenMetres) {
  TopDownOptions options;
  options.origin_marker_radius_px = 0;
  const auto render = RenderTopDown({}, options);
  ASSERT_TRUE(render.ok());
  const RgbImage& image = render->image;
  for (int k = 1; k <= 5; ++k) {
    EXPECT_EQ(image.At(500, 500 - 100 * k), options.ring_colour) << "ring " << k << " top";
    EXPECT_EQ(image.At(500 + 100 * k, 500), options.ring_colour) << "ring " << k << " right";
  }
  EXPECT_EQ(image.At(500, 450), options.background);
  // The 60 and 70 m rings reach into the corners: the 60 m ring crosses the diagonal
  // within a pixel of 600 / sqrt(2) px from the centre.
  const int r60 = static_cast<int>(std::lround(600 / std::sqrt(2.0)));
  int ring_pixels_near_diagonal = 0;
  for (int d = -1; d <= 1; ++d) {
    for (int e = -1; e <= 1; ++e) {
      ring_pixels_near_diagonal += image.At(500 + r60 + d, 500 + r60 + e) == options.ring_colour;
    }
  }
  EXPECT_GE(ring_pixels_near_diagonal, 1);
}

TEST(TopDownTest, RenderingIsDeterministic) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-60.0f, 60.0f);
  std::vector<TopDownPoint> points(5000);
  for (auto& p : points) p = {value(rng), value(rng), value(rng) / 10.0f, value(rng) + 60.0f};
  const auto a = RenderTopDown(points);
  const auto b = RenderTopDown(points);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->image.pixels, b->image.pixels);
  EXPECT_EQ(a->drawn + a->outside_extent, points.size());
}

TEST(TopDownTest, InvalidOptionsNameTheField) {
  const auto expect_error_naming = [](TopDownOptions options, const std::string& field) {
    const auto render = RenderTopDown({}, options);
    ASSERT_FALSE(render.ok()) << field;
    EXPECT_NE(render.error().message.find(field), std::string::npos) << render.error().message;
  };
  TopDownOptions options;
  options.metres_per_pixel = 0;
  expect_error_naming(options, "metres_per_pixel");
  options = {};
  options.half_extent_m = std::numeric_limits<double>::quiet_NaN();
  expect_error_naming(options, "half_extent_m");
  options = {};
  options.metres_per_pixel = 0.001;  // 100001 px square
  expect_error_naming(options, "half_extent_m");
  options = {};
  options.z_max_m = options.z_min_m;
  expect_error_naming(options, "z_max_m");
  options = {};
  options.intensity_max = -1;
  expect_error_naming(options, "intensity_max");
  options = {};
  options.ring_spacing_m = 0.05;
  expect_error_naming(options, "ring_spacing_m");
  options = {};
  options.origin_marker_radius_px = -1;
  expect_error_naming(options, "origin_marker_radius_px");
}

}  // namespace
}  // namespace flat2d::maps
