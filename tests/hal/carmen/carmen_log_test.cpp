// CARMEN log reading: FLASER and ROBOTLASER1 fields, malformed lines counted and skipped,
// gzip files, and the real corrected benchmark logs.
#include "hal/carmen/carmen_log.hpp"

#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/testing/data_path.hpp"

namespace flat2d::hal::carmen {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(CarmenLogTest, ReadsFlaserFields) {
  CarmenLogReader reader = CarmenLogReader::FromString(
      "# comment\nPARAM robot_use_laser on nohost 0\nODOM 0 0 0 0 0 0 0.1 pippo 0.1\n"
      "FLASER 4 1.5 2.25 3 81.91 0.5 -0.25 1.5 0.6 -0.2 1.4 21.0199 pippo 21.5\n");
  LaserScan scan;
  ASSERT_TRUE(reader.Next(scan));
  EXPECT_EQ(scan.message, CarmenMessage::kFlaser);
  ASSERT_EQ(scan.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(scan.ranges[1], 2.25F);
  EXPECT_FLOAT_EQ(scan.ranges[3], 81.91F);
  EXPECT_DOUBLE_EQ(scan.laser_pose.x, 0.5);
  EXPECT_DOUBLE_EQ(scan.laser_pose.y, -0.25);
  EXPECT_DOUBLE_EQ(scan.laser_pose.theta, 1.5);
  EXPECT_DOUBLE_EQ(scan.robot_pose.x, 0.6);
  EXPECT_DOUBLE_EQ(scan.robot_pose.theta, 1.4);
  EXPECT_DOUBLE_EQ(scan.timestamp, 21.0199);
  EXPECT_DOUBLE_EQ(scan.angle_min, -0.5 * kPi);
  EXPECT_DOUBLE_EQ(scan.angle_increment, kPi / 4.0);  // even count: pi / n
  EXPECT_FALSE(reader.Next(scan));
  EXPECT_EQ(reader.stats().lines, 4u);
  EXPECT_EQ(reader.stats().flaser, 1u);
  EXPECT_EQ(reader.stats().odometry, 1u);
  EXPECT_EQ(reader.stats().other, 2u);
  EXPECT_EQ(reader.stats().malformed, 0u);
}

TEST(CarmenLogTest, OddBeamCountsIncludeBothEnds) {
  CarmenLogReader reader =
      CarmenLogReader::FromString("FLASER 3 1 2 3 0 0 0 0 0 0 5 h 5");
  LaserScan scan;
  ASSERT_TRUE(reader.Next(scan));
  EXPECT_DOUBLE_EQ(scan.angle_min + 2 * scan.angle_increment, 0.5 * kPi);
}

TEST(CarmenLogTest, ReadsRobotLaser1Fields) {
  CarmenLogReader reader = CarmenLogReader::FromString(
      "ROBOTLASER1 0 -1.5708 3.14159 0.0174533 81.9 0.01 0 3 1.0 2.0 3.0 2 7 8 "
      "1.1 2.2 0.3 1.0 2.0 0.25 0.1 0.0 0.5 0.2 0.3 1234.5 host 1234.6\n");
  LaserScan scan;
  ASSERT_TRUE(reader.Next(scan));
  EXPECT_EQ(scan.message, CarmenMessage::kRobotLaser1);
  EXPECT_DOUBLE_EQ(scan.angle_min, -1.5708);
  EXPECT_DOUBLE_EQ(scan.angle_increment, 0.0174533);
  EXPECT_DOUBLE_EQ(scan.max_range, 81.9);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(scan.ranges[2], 3.0F);
  EXPECT_DOUBLE_EQ(scan.laser_pose.x, 1.1);
  EXPECT_DOUBLE_EQ(scan.laser_pose.theta, 0.3);
  EXPECT_DOUBLE_EQ(scan.robot_pose.theta, 0.25);
  EXPECT_DOUBLE_EQ(scan.timestamp, 1234.5);
  EXPECT_EQ(reader.stats().robotlaser, 1u);
}

TEST(CarmenLogTest, MalformedLinesAreCountedAndSkipped) {
  CarmenLogReader reader = CarmenLogReader::FromString(
      "FLASER 3 1 2\n"                                  // truncated
      "FLASER x 1 2 3 0 0 0 0 0 0 5 h 5\n"              // bad count
      "FLASER 3 1 nan 3 0 0 0 0 0 0 5 h 5\n"            // non-finite range
      "FLASER 2 1 2 0 0 0 0 0 0 6 h 6\n"                // good
      "ROBOTLASER1 0 0 3 0.1 80 0.01 0 2 1 2\n"         // truncated
      "FLASER 2 1 2 0 0 0 0 0 0 7 h 7");                // good, no final newline
  LaserScan scan;
  ASSERT_TRUE(reader.Next(scan));
  EXPECT_DOUBLE_EQ(scan.timestamp, 6.0);
  ASSERT_TRUE(reader.Next(scan));
  EXPECT_DOUBLE_EQ(scan.timestamp, 7.0);
  EXPECT_FALSE(reader.Next(scan));
  EXPECT_EQ(reader.stats().malformed, 4u);
  ASSERT_EQ(reader.stats().first_malformed.size(), 4u);
  EXPECT_EQ(reader.stats().first_malformed[0].line, 1u);
  EXPECT_EQ(reader.stats().first_malformed[3].line, 5u);
  EXPECT_NE(reader.stats().first_malformed[1].reason.find("count"), std::string::npos);
}

TEST(CarmenLogTest, ReadsGzipFilesAndLongLines) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "flat2d_carmen_log_test.log.gz";
  std::string long_line = "FLASER 30000";
  for (int i = 0; i < 30000; ++i) long_line += " 1.25";
  long_line += " 0 0 0 0 0 0 9 h 9\n";
  gzFile file = gzopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  const std::string text = "ODOM 0 0 0 0 0 0 1 h 1\n" + long_line;
  ASSERT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  gzclose(file);
  Result<CarmenScans> scans = ReadCarmenLaserScans(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(scans.ok()) << scans.error().message;
  ASSERT_EQ(scans->scans.size(), 1u);
  EXPECT_EQ(scans->scans[0].ranges.size(), 30000u);
  EXPECT_DOUBLE_EQ(scans->scans[0].timestamp, 9.0);
  EXPECT_EQ(scans->stats.odometry, 1u);
  EXPECT_FALSE(ReadCarmenLaserScans("/nonexistent/x.log.gz").ok());
}

TEST(CarmenLogTest, RealCorrectedLogs) {
  struct Expected {
    const char* file;
    std::size_t scans;
    std::size_t beams;
  };
  for (const Expected& e : {Expected{"intel-corrected.log.gz", 910, 180},
                            Expected{"aces-corrected.log.gz", 440, 180},
                            Expected{"csail-corrected.log.gz", 406, 361},
                            Expected{"freiburg-079-corrected.log.gz", 4791, 360}}) {
    FLAT2D_REQUIRE_DATA(path, std::string("slam2d/corrected_logs/") + e.file);
    Result<CarmenScans> log = ReadCarmenLaserScans(path);
    ASSERT_TRUE(log.ok()) << log.error().message;
    // Counts from PROVENANCE.md; every FLASER line parses.
    EXPECT_EQ(log->scans.size(), e.scans) << e.file;
    EXPECT_EQ(log->stats.malformed, 0u) << e.file;
    for (const LaserScan& scan : log->scans) ASSERT_EQ(scan.ranges.size(), e.beams) << e.file;
  }
}

}  // namespace
}  // namespace flat2d::hal::carmen
