#include "maps/render/image.hpp"

#include <limits>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

TEST(RgbImageTest, ConstructorFillsAndAccessorsAddressRowMajor) {
  RgbImage image(4, 3, Rgb{1, 2, 3});
  ASSERT_EQ(image.pixels.size(), 4u * 3u * 3u);
  EXPECT_EQ(image.At(3, 2), (Rgb{1, 2, 3}));

  image.Set(2, 1, Rgb{10, 20, 30});
  // Row 1, column 2 of a 4-wide image starts at byte (1 * 4 + 2) * 3.
  EXPECT_EQ(image.pixels[18], 10);
  EXPECT_EQ(image.pixels[19], 20);
  EXPECT_EQ(image.pixels[20], 30);
  EXPECT_EQ(image.At(2, 1), (Rgb{10, 20, 30}));
  EXPECT_EQ(image.At(1, 2), (Rgb{1, 2, 3}));

  image.Fill(Rgb{7, 8, 9});
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) EXPECT_EQ(image.At(col, row), (Rgb{7, 8, 9}));
  }
}

TEST(RgbImageTest, SetClippedIgnoresPixelsOffTheImage) {
  RgbImage image(2, 2);
  const std::vector<std::uint8_t> before = image.pixels;
  image.SetClipped(-1, 0, Rgb{255, 0, 0});
  image.SetClipped(0, 2, Rgb{255, 0, 0});
  image.SetClipped(2, 1, Rgb{255, 0, 0});
  EXPECT_EQ(image.pixels, before);
  image.SetClipped(1, 1, Rgb{255, 0, 0});
  EXPECT_EQ(image.At(1, 1), (Rgb{255, 0, 0}));
}

TEST(RgbImageTest, NegativeSizeGivesEmptyImage) {
  const RgbImage image(-3, 5);
  EXPECT_EQ(image.width, 0);
  EXPECT_TRUE(image.pixels.empty());
}

TEST(ViridisTest, EndpointsAreThePublishedViridisColours) {
  EXPECT_EQ(Viridis(0.0), (Rgb{0x44, 0x01, 0x54}));
  EXPECT_EQ(Viridis(1.0), (Rgb{0xfd, 0xe7, 0x25}));
  EXPECT_EQ(Viridis(0.5), (Rgb{0x21, 0x90, 0x8c}));
}

TEST(ViridisTest, OutOfRangeAndNanClampToEndpoints) {
  EXPECT_EQ(Viridis(-4.0), Viridis(0.0));
  EXPECT_EQ(Viridis(7.0), Viridis(1.0));
  EXPECT_EQ(Viridis(std::numeric_limits<double>::quiet_NaN()), Viridis(0.0));
}

TEST(ViridisTest, LumaRisesAcrossTheRange) {
  // Fine steps may tie or dip by rounding (each channel is rounded to a level, at most
  // half a level of luma); coarse steps must rise strictly.
  constexpr int kFine = 1000;
  for (int i = 0; i < kFine; ++i) {
    const double a = Luma(Viridis(static_cast<double>(i) / kFine));
    const double b = Luma(Viridis(static_cast<double>(i + 1) / kFine));
    EXPECT_GE(b, a - 0.5) << "t = " << static_cast<double>(i) / kFine;
  }
  constexpr int kCoarse = 64;
  for (int i = 0; i < kCoarse; ++i) {
    const double a = Luma(Viridis(static_cast<double>(i) / kCoarse));
    const double b = Luma(Viridis(static_cast<double>(i + 1) / kCoarse));
    EXPECT_GT(b, a) << "t = " << static_cast<double>(i) / kCoarse;
  }
  EXPECT_GT(Luma(Viridis(1.0)) - Luma(Viridis(0.0)), 180.0);
}

}  // namespace
}  // namespace flat2d::maps
