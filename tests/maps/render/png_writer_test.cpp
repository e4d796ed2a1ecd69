#include "maps/render/png_writer.hpp"

#include <png.h>

#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test under gtest's temp dir, removed afterwards.
class PngFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("flat2d_png_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

RgbImage RandomImage(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  RgbImage image(width, height);
  for (auto& value : image.pixels) value = static_cast<std::uint8_t>(byte(rng));
  return image;
}

void WriteBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes, std::size_t n) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(n));
}

// A PNG in another pixel format, made with libpng's simplified API so the decoder is
// checked against files it did not write itself.
std::vector<std::uint8_t> EncodeWithLibpng(int width, int height, png_uint_32 format,
                                           const void* pixels, const void* colormap = nullptr,
                                           int colormap_entries = 0) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = format;
  image.colormap_entries = static_cast<png_uint_32>(colormap_entries);
  png_alloc_size_t size = 0;
  EXPECT_NE(png_image_write_to_memory(&image, nullptr, &size, 0, pixels, 0, colormap), 0);
  std::vector<std::uint8_t> bytes(size);
  EXPECT_NE(png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels, 0, colormap), 0)
      << image.message;
  bytes.resize(size);
  return bytes;
}

TEST_F(PngFileTest, WriteReadRoundTripIsPixelExact) {
  const unsigned seed = 42;
  const RgbImage image = RandomImage(37, 23, seed);
  const fs::path path = dir_ / "random.png";
  const Status written = WritePng(image, path);
  ASSERT_TRUE(written.ok()) << written.error().message;

  const Result<RgbImage> read = ReadPng(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->width, 37);
  EXPECT_EQ(read->height, 23);
  EXPECT_EQ(read->pixels, image.pixels) << "seed " << seed;
}

TEST(PngMemoryTest, EncodeDecodeRoundTripAndDeterministicBytes) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const RgbImage image =
        RandomImage(1 + static_cast<int>(seed) * 7, 1 + static_cast<int>(seed), seed);
    const auto bytes = EncodePng(image);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const auto again = EncodePng(image);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(*bytes, *again) << "seed " << seed;
    const auto decoded = DecodePng(*bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->pixels, image.pixels) << "seed " << seed;
  }
}

TEST(PngMemoryTest, EncodeRejectsEmptyAndInconsistentImages) {
  EXPECT_FALSE(EncodePng(RgbImage()).ok());
  RgbImage short_buffer(4, 4);
  short_buffer.pixels.pop_back();
  const auto result = EncodePng(short_buffer);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("expected 48"), std::string::npos)
      << result.error().message;
}

TEST_F(PngFileTest, WriteToUnwritablePathNamesThePath) {
  const fs::path path = dir_ / "no_such_dir" / "out.png";
  const Status written = WritePng(RgbImage(2, 2), path);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos)
      << written.error().message;
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(PngFileTest, ReadMissingFileNamesThePath) {
  const fs::path path = dir_ / "missing.png";
  const Result<RgbImage> read = ReadPng(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().message.find(path.string()), std::string::npos) << read.error().message;
}

TEST_F(PngFileTest, TruncatedFilesFailCleanly) {
  const auto bytes = EncodePng(RandomImage(64, 48, 7));
  ASSERT_TRUE(bytes.ok());
  const fs::path path = dir_ / "truncated.png";
  // Empty, inside the signature, just the signature, inside IHDR, inside IDAT, and one
  // byte short of IEND's CRC.
  for (const std::size_t keep : {std::size_t{0}, std::size_t{5}, std::size_t{8}, std::size_t{20},
                                 bytes->size() / 2, bytes->size() - 1}) {
    WriteBytes(path, *bytes, keep);
    const Result<RgbImage> read = ReadPng(path);
    ASSERT_FALSE(read.ok()) << "kept " << keep << " of " << bytes->size() << " bytes";
    EXPECT_NE(read.error().message.find(path.string()), std::string::npos) << read.error().message;
  }
}

TEST(PngMemoryTest, CorruptedImageDataFailsCleanly) {
  auto bytes = EncodePng(RandomImage(64, 48, 9));
  ASSERT_TRUE(bytes.ok());
  // Flip bytes in the middle of IDAT: the chunk CRC no longer matches, which libpng
  // treats as an error for critical chunks.
  for (std::size_t i = bytes->size() / 2; i < bytes->size() / 2 + 16; ++i) (*bytes)[i] ^= 0x5a;
  EXPECT_FALSE(DecodePng(*bytes).ok());
}

TEST(PngMemoryTest, GreyRgbaSixteenBitAndPaletteDecodeToRgb) {
  const std::vector<std::uint8_t> grey = {0, 100, 200, 255};
  auto decoded = DecodePng(EncodeWithLibpng(2, 2, PNG_FORMAT_GRAY, grey.data()));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(decoded->At(1, 0), (Rgb{100, 100, 100}));
  EXPECT_EQ(decoded->At(0, 1), (Rgb{200, 200, 200}));

  const std::vector<std::uint8_t> rgba = {10, 20, 30, 255, 40, 50, 60, 255};
  decoded = DecodePng(EncodeWithLibpng(2, 1, PNG_FORMAT_RGBA, rgba.data()));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(decoded->At(0, 0), (Rgb{10, 20, 30}));
  EXPECT_EQ(decoded->At(1, 0), (Rgb{40, 50, 60}));

  // 16-bit samples keep their high byte.
  const std::vector<std::uint16_t> grey16 = {0x1234, 0xff00};
  decoded = DecodePng(EncodeWithLibpng(2, 1, PNG_FORMAT_LINEAR_Y, grey16.data()));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(decoded->At(0, 0), (Rgb{0x12, 0x12, 0x12}));
  EXPECT_EQ(decoded->At(1, 0), (Rgb{0xff, 0xff, 0xff}));

  const std::vector<std::uint8_t> palette = {255, 0, 0, 0, 0, 255};
  const std::vector<std::uint8_t> indices = {1, 0, 0};
  decoded =
      DecodePng(EncodeWithLibpng(3, 1, PNG_FORMAT_RGB_COLORMAP, indices.data(), palette.data(), 2));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(decoded->At(0, 0), (Rgb{0, 0, 255}));
  EXPECT_EQ(decoded->At(2, 0), (Rgb{255, 0, 0}));
}

TEST(PngMemoryTest, NonPngBytesAreRejected) {
  const std::vector<std::uint8_t> text = {'h', 'e', 'l', 'l', 'o', ',', ' ', 'w', 'o', 'r'};
  const auto decoded = DecodePng(text);
  ASSERT_FALSE(decoded.ok());
  EXPECT_NE(decoded.error().message.find("signature"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::maps
