// KITTI .bin scans built inline: records decode in order, and a size that is not a whole
// number of records is an error naming the file and the size.
#include "hal/cloud/kitti_bin_file.hpp"

#include <cstring>
#include <string>

#include <gtest/gtest.h>

namespace flat2d::hal::cloud {
namespace {

std::string Records(std::initializer_list<float> values) {
  std::string bytes(values.size() * sizeof(float), '\0');
  std::memcpy(bytes.data(), std::data(values), bytes.size());
  return bytes;
}

TEST(KittiBinFile, RecordsAreXyzAndReflectance) {
  const Result<PointCloud> cloud = ParseKittiBin(Records({52.9f, 0.023f, 2.0f, 0.08f, -4.5f, 1.5f, -1.75f, 1.0f}),
                                                 "000000.bin");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 2u);
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(52.9f, 0.023f, 2.0f));
  EXPECT_EQ(cloud->points[1], Eigen::Vector3f(-4.5f, 1.5f, -1.75f));
  EXPECT_EQ(cloud->intensity, (std::vector<float>{0.08f, 1.0f}));
  EXPECT_TRUE(cloud->ring.empty());
  EXPECT_FALSE(cloud->organized());
  EXPECT_TRUE(ParseKittiBin("", "empty.bin")->points.empty());
}

TEST(KittiBinFile, PartialRecordIsAnErrorNamingFileAndSize) {
  EXPECT_EQ(ParseKittiBin(Records({1, 2, 3, 4, 5}), "cut.bin").error().message,
            "cut.bin: size 20 bytes is not a multiple of 16 (x, y, z, reflectance as float32)");
  EXPECT_EQ(ReadKittiBin("/nonexistent/000000.bin").error().message, "/nonexistent/000000.bin: cannot open");
}

}  // namespace
}  // namespace flat2d::hal::cloud
