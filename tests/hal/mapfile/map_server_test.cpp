#include "hal/mapfile/map_server.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace flat2d::hal::mapfile {
namespace {

class MapServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("flat2d_map_server_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::filesystem::path dir_;
};

GrayMap Sample() {
  GrayMap map;
  map.width = 3;
  map.height = 2;
  map.resolution_m = 0.05;
  map.origin = {-12.5, 3.25};
  map.pixels = {0, 128, 254, 205, 7, 255};
  return map;
}

TEST_F(MapServerTest, RoundTripKeepsPixelsResolutionAndOrigin) {
  ASSERT_TRUE(WriteMapServer(Sample(), dir_ / "grid", {"0 = slammable", "128 = hazard"}).ok());
  std::ifstream yaml(dir_ / "grid.yaml");
  std::stringstream contents;
  contents << yaml.rdbuf();
  const std::string text = contents.str();
  EXPECT_EQ(text,
            "# 0 = slammable\n# 128 = hazard\nimage: grid.pgm\nresolution: 0.05\norigin: [-12.5, 3.25, 0.0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  const auto read = ReadMapServer(dir_ / "grid.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->width, 3);
  EXPECT_EQ(read->height, 2);
  EXPECT_EQ(read->pixels, Sample().pixels);
  EXPECT_DOUBLE_EQ(read->resolution_m, 0.05);
  EXPECT_EQ(read->origin, Eigen::Vector2d(-12.5, 3.25));
}

TEST_F(MapServerTest, ReadsHeaderCommentsAsGimpWritesThem) {
  Write("a.pgm", std::string("P5\n# CREATOR: GIMP\n2 1\n255\n") + '\x00' + '\xfe');
  Write("a.yaml", "image: a.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  const auto read = ReadMapServer(dir_ / "a.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->pixels, (std::vector<std::uint8_t>{0, 254}));
}

TEST_F(MapServerTest, BadFilesAreNamedErrors) {
  Write("short.pgm", "P5\n4 4\n255\nab");
  Write("short.yaml", "image: short.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(ReadMapServer(dir_ / "short.yaml").error().message.find("shorter than 4 x 4"), std::string::npos);
  Write("ascii.pgm", "P2\n1 1\n255\n0\n");
  Write("ascii.yaml", "image: ascii.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(ReadMapServer(dir_ / "ascii.yaml").error().message.find("not a binary PGM"), std::string::npos);
  Write("noimage.yaml", "resolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(ReadMapServer(dir_ / "noimage.yaml").error().message.find("needs image"), std::string::npos);
  Write("yaw.yaml", "image: ascii.pgm\nresolution: 0.1\norigin: [0, 0, 0.5]\n");
  EXPECT_NE(ReadMapServer(dir_ / "yaw.yaml").error().message.find("yaw"), std::string::npos);
  Write("res.yaml", "image: ascii.pgm\nresolution: -1\norigin: [0, 0, 0]\n");
  EXPECT_NE(ReadMapServer(dir_ / "res.yaml").error().message.find("resolution"), std::string::npos);
  Write("broken.yaml", "image: [unclosed\n");
  EXPECT_FALSE(ReadMapServer(dir_ / "broken.yaml").ok());
  EXPECT_FALSE(ReadMapServer(dir_ / "missing.yaml").ok());
  GrayMap bad = Sample();
  bad.pixels.pop_back();
  EXPECT_FALSE(WriteMapServer(bad, dir_ / "bad").ok());
}

}  // namespace
}  // namespace flat2d::hal::mapfile
