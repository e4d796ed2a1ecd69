// TUM depth PNGs written here with libpng's own writer (16-bit grey with known values, and
// an 8-bit grey image that must be refused), and association lists.
#include "hal/cloud/tum_depth_png.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::hal::cloud {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test under gtest's temp dir, removed afterwards.
class TumDepthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("flat2d_tum_depth_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

// Holds setjmp: nothing here owns resources.
bool RunWrite(png_structp png, png_infop info, int width, int height, int bit_depth,
              const std::vector<png_byte>& pixels) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth,
               PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t row_bytes = static_cast<std::size_t>(width) * (bit_depth / 8);
  for (int row = 0; row < height; ++row) png_write_row(png, pixels.data() + static_cast<std::size_t>(row) * row_bytes);
  png_write_end(png, nullptr);
  return true;
}

// A grey PNG of `values` (row-major), 8 or 16 bits, written by libpng.
void WriteGreyPng(const fs::path& path, int width, int height, int bit_depth, const std::vector<unsigned>& values) {
  std::vector<png_byte> pixels;
  for (const unsigned value : values) {
    if (bit_depth == 16) pixels.push_back(static_cast<png_byte>(value >> 8));  // PNG is big-endian
    pixels.push_back(static_cast<png_byte>(value & 0xff));
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  const bool written = RunWrite(png, info, width, height, bit_depth, pixels);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
  ASSERT_TRUE(written);
}

TEST_F(TumDepthTest, SixteenBitGreyIsDepthOverScale) {
  const fs::path path = dir_ / "depth.png";
  WriteGreyPng(path, 3, 2, 16, {0, 5000, 65535, 1, 256, 12345});
  const Result<DepthImage> image = ReadTumDepthPng(path);
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_EQ(image->width, 3);
  EXPECT_EQ(image->height, 2);
  EXPECT_EQ(image->at(0, 0), 0.0f);  // no data
  EXPECT_FLOAT_EQ(image->at(0, 1), 1.0f);
  EXPECT_FLOAT_EQ(image->at(0, 2), 13.107f);
  EXPECT_FLOAT_EQ(image->at(1, 0), 0.0002f);
  EXPECT_FLOAT_EQ(image->at(1, 1), 0.0512f);  // high byte 1, low byte 0: byte order matters
  EXPECT_FLOAT_EQ(image->at(1, 2), 2.469f);
  const Result<DepthImage> millimetres = ReadTumDepthPng(path, 1000.0);
  ASSERT_TRUE(millimetres.ok());
  EXPECT_FLOAT_EQ(millimetres->at(0, 1), 5.0f);
}

TEST_F(TumDepthTest, OtherPngsAndFilesAreErrorsNamingTheFile) {
  const fs::path grey8 = dir_ / "grey8.png";
  WriteGreyPng(grey8, 2, 2, 8, {0, 1, 2, 3});
  EXPECT_EQ(ReadTumDepthPng(grey8).error().message, grey8.string() + ": 8-bit grey PNG, expected 16-bit grey depth");
  const fs::path text = dir_ / "depth.png.txt";
  std::ofstream(text) << "not a png";
  EXPECT_EQ(ReadTumDepthPng(text).error().message, text.string() + ": not a PNG file");
  const fs::path cut = dir_ / "cut.png";
  WriteGreyPng(cut, 4, 4, 16, std::vector<unsigned>(16, 7));
  fs::resize_file(cut, 40);
  EXPECT_EQ(ReadTumDepthPng(cut).error().message.rfind(cut.string() + ": bad PNG ", 0), 0u)
      << ReadTumDepthPng(cut).error().message;
  EXPECT_EQ(ReadTumDepthPng(dir_ / "none.png").error().message, (dir_ / "none.png").string() + ": cannot open");
  EXPECT_FALSE(ReadTumDepthPng(grey8, 0.0).ok());
}

TEST_F(TumDepthTest, AssociationListResolvesFilesAgainstItsFolder) {
  const fs::path list = dir_ / "depth.txt";
  std::ofstream(list) << "# depth maps\n# timestamp filename\n1305031229.528784 depth/1305031229.528784.png\n\n"
                         "1305031229.564442 /abs/1.png  # comment\n";
  const Result<std::vector<DepthFrame>> frames = ReadTumAssociationList(list);
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  ASSERT_EQ(frames->size(), 2u);
  EXPECT_DOUBLE_EQ((*frames)[0].time_s, 1305031229.528784);
  EXPECT_EQ((*frames)[0].file, dir_ / "depth" / "1305031229.528784.png");
  EXPECT_EQ((*frames)[1].file, fs::path("/abs/1.png"));
  EXPECT_EQ(ParseTumAssociationList("1.0 a.png extra\n", "d.txt", "/x").error().message,
            "d.txt:1: expected 'timestamp filename'");
  EXPECT_EQ(ParseTumAssociationList("# c\nnow a.png\n", "d.txt", "/x").error().message, "d.txt:2: bad timestamp 'now'");
}

}  // namespace
}  // namespace flat2d::hal::cloud
