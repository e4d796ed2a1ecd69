// PCD files written by WritePcd, read back by ReadPcd: points (NaN kept), intensity and
// ring as given, every channel combination, and the errors.
#include "hal/cloud/pcd_writer.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "hal/cloud/pcd_file.hpp"

namespace flat2d::hal::cloud {
namespace {

std::filesystem::path TempPcd(const std::string& name) { return std::filesystem::path(::testing::TempDir()) / name; }

PointCloud ThreePoints() {
  PointCloud cloud;
  cloud.points = {{1.5F, -2.0F, 0.25F}, {3.0F, 4.0F, -5.0F}, {-0.125F, 1e3F, 7.0F}};
  return cloud;
}

// Writes `cloud` to a temporary file named `name` and reads it back.
Result<PointCloud> RoundTrip(const PointCloud& cloud, const std::string& name) {
  if (Status s = WritePcd(TempPcd(name), cloud); !s.ok()) return s.error();
  return ReadPcd(TempPcd(name));
}

TEST(PcdWriter, PointsIntensityAndRingReadBack) {
  PointCloud cloud = ThreePoints();
  cloud.intensity = {0.0F, 12.5F, 255.0F};
  cloud.ring = {0, 31, 65535};
  const Result<PointCloud> read = RoundTrip(cloud, "all.pcd");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->points, cloud.points);
  EXPECT_EQ(read->intensity, cloud.intensity);
  EXPECT_EQ(read->ring, cloud.ring);
  EXPECT_FALSE(read->organized());
}

TEST(PcdWriter, ChannelsMayBeLeftOut) {
  PointCloud ring_only = ThreePoints();
  ring_only.ring = {4, 5, 6};
  const Result<PointCloud> read = RoundTrip(ring_only, "ring_only.pcd");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->points, ring_only.points);
  EXPECT_TRUE(read->intensity.empty());
  EXPECT_EQ(read->ring, ring_only.ring);

  const Result<PointCloud> bare = RoundTrip(ThreePoints(), "bare.pcd");
  ASSERT_TRUE(bare.ok()) << bare.error().message;
  EXPECT_EQ(bare->points, ThreePoints().points);
  EXPECT_TRUE(bare->ring.empty());
}

TEST(PcdWriter, NanPointsStayNanAndAnEmptyCloudIsAFile) {
  PointCloud cloud = ThreePoints();
  cloud.points[1] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  const Result<PointCloud> read = RoundTrip(cloud, "nan.pcd");
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_EQ(read->points.size(), 3U);
  EXPECT_TRUE(std::isnan(read->points[1].x()));
  EXPECT_EQ(read->points[2], cloud.points[2]);

  const Result<PointCloud> empty = RoundTrip(PointCloud{}, "empty.pcd");
  ASSERT_TRUE(empty.ok()) << empty.error().message;
  EXPECT_TRUE(empty->points.empty());
}

TEST(PcdWriter, ChannelOfTheWrongLengthAndUnwritablePathAreErrors) {
  PointCloud cloud = ThreePoints();
  cloud.intensity = {1.0F};
  const Status short_channel = WritePcd(TempPcd("short.pcd"), cloud);
  ASSERT_FALSE(short_channel.ok());
  EXPECT_NE(short_channel.error().message.find("1 intensity values for 3 points"), std::string::npos)
      << short_channel.error().message;
  EXPECT_FALSE(std::filesystem::exists(TempPcd("short.pcd")));

  const Status unwritable = WritePcd("/nonexistent-dir/x.pcd", ThreePoints());
  ASSERT_FALSE(unwritable.ok());
  EXPECT_NE(unwritable.error().message.find("/nonexistent-dir/x.pcd"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::hal::cloud
