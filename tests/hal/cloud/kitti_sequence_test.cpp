// KITTI sequence directories built in a temporary directory: scans in name order with their
// times.txt stamps, and every malformed case an error naming the file (and line); then the
// real KITTI 00 excerpt's 16 scans at 10 Hz.
#include "hal/cloud/kitti_sequence.hpp"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/testing/data_path.hpp"

namespace flat2d::hal::cloud {
namespace {

namespace fs = std::filesystem;

class KittiSequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("kitti_sequence_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "velodyne");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void Write(const fs::path& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }

  fs::path dir_;
};

TEST_F(KittiSequenceTest, ScansInNameOrderWithTheirTimes) {
  for (const char* name : {"000002.bin", "000000.bin", "000001.bin"}) Write(fs::path("velodyne") / name, "");
  Write("velodyne/readme.txt", "not a scan");
  Write("times.txt", "0.000000e+00\n1.037359e-01\r\n2.073381e-01\n3.110000e-01\n");  // one time more than scans
  const Result<KittiSequence> sequence = OpenKittiSequence(dir_);
  ASSERT_TRUE(sequence.ok()) << sequence.error().message;
  ASSERT_EQ(sequence->scans.size(), 3u);
  EXPECT_EQ(sequence->scans[0].filename(), "000000.bin");
  EXPECT_EQ(sequence->scans[2].filename(), "000002.bin");
  EXPECT_EQ(sequence->stamps, (std::vector<TimeNs>{0, 103'735'900, 207'338'100}));
  EXPECT_TRUE(IsKittiSequence(dir_));
  EXPECT_FALSE(IsKittiSequence(dir_ / "times.txt"));
}

TEST_F(KittiSequenceTest, MalformedDirectoriesAreErrorsNamingTheFile) {
  EXPECT_EQ(OpenKittiSequence(dir_ / "velodyne").error().message,
            (dir_ / "velodyne").string() + ": no velodyne/ directory (not a KITTI sequence)");
  EXPECT_EQ(OpenKittiSequence(dir_).error().message, (dir_ / "velodyne").string() + ": no .bin scan");
  Write("velodyne/000000.bin", "");
  Write("velodyne/000001.bin", "");
  EXPECT_EQ(OpenKittiSequence(dir_).error().message, (dir_ / "times.txt").string() + ": cannot open");
  Write("times.txt", "0.0\n");
  EXPECT_EQ(OpenKittiSequence(dir_).error().message, (dir_ / "times.txt").string() + ": 1 times for 2 scans");
}

TEST(KittiTimes, BadLinesAreErrorsNamingTheLine) {
  EXPECT_EQ(ParseKittiTimes("0.0\n\n0.1 0.2\n", "times.txt").error().message,
            "times.txt: line 3: expected one time in seconds, >= 0");
  EXPECT_EQ(ParseKittiTimes("0.0\nabc\n", "times.txt").error().message, "times.txt: line 2: expected one time in seconds, >= 0");
  EXPECT_EQ(ParseKittiTimes("-0.1\n", "times.txt").error().message, "times.txt: line 1: expected one time in seconds, >= 0");
  EXPECT_EQ(ParseKittiTimes("0.2\n0.1\n", "times.txt").error().message, "times.txt: line 2: times must increase");
  EXPECT_EQ(ParseKittiTimes("nan\n", "times.txt").error().message, "times.txt: line 1: expected one time in seconds, >= 0");
  EXPECT_TRUE(ParseKittiTimes("", "times.txt")->empty());
}

TEST(KittiSequenceRealData, Kitti00ExcerptHas16ScansAt10Hz) {
  FLAT2D_REQUIRE_DATA(dir, "lidar3d/kitti_odometry_00_frames_000000-000015");
  const Result<KittiSequence> sequence = OpenKittiSequence(dir);
  ASSERT_TRUE(sequence.ok()) << sequence.error().message;
  ASSERT_EQ(sequence->scans.size(), 16u);
  EXPECT_EQ(sequence->scans.back().filename(), "000015.bin");
  EXPECT_EQ(sequence->stamps[1], 103'735'900);  // times.txt line 2: 1.037359e-01
  for (std::size_t i = 1; i < 16; ++i) EXPECT_NEAR(static_cast<double>(sequence->stamps[i] - sequence->stamps[i - 1]) * 1e-9, 0.1036, 0.002);
}

}  // namespace
}  // namespace flat2d::hal::cloud
