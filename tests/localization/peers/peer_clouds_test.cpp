// The registration peers' input clouds: which points survive (NaN, zero-range, depth 0 and
// beyond the limit do not), the pinhole unprojection checked by hand, the HDL-32E scan's
// count against its known zero-range returns, and the two libraries' copies.
#include "localization/peers/peer_clouds.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tests/testing/data_path.hpp"

namespace flat2d::localization::peers {
namespace {

TEST(PeerClouds, DropsNanAndZeroRangePoints) {
  hal::cloud::PointCloud cloud;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points = {{1, 2, 3}, {0, 0, 0}, {nan, nan, nan}, {0, 0, 1e-3f}, {nan, 1, 1}, {-4, 5, -6}};
  const Points points = MeasuredPoints(cloud);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(points[1], Eigen::Vector3f(0, 0, 1e-3f));  // near the origin is a measurement
  EXPECT_EQ(points[2], Eigen::Vector3f(-4, 5, -6));
}

TEST(PeerClouds, UnprojectsDepthThroughThePinhole) {
  hal::cloud::DepthImage image{.width = 4, .height = 3, .depth_m = std::vector<float>(12, 0.0f)};
  image.depth_m[0 * 4 + 3] = 2.0f;    // row 0, col 3
  image.depth_m[2 * 4 + 0] = 8.0f;    // row 2, col 0: at the limit, kept
  image.depth_m[1 * 4 + 1] = 8.01f;   // beyond it
  const PinholeIntrinsics intrinsics{.fx = 2.0, .fy = 4.0, .cx = 1.5, .cy = 1.0};
  const Points points = UnprojectDepth(image, intrinsics, 8.0);
  ASSERT_EQ(points.size(), 2u);
  // x = (u - cx) z / fx, y = (v - cy) z / fy: (3 - 1.5) 2 / 2, (0 - 1) 2 / 4.
  EXPECT_FLOAT_EQ(points[0].x(), 1.5f);
  EXPECT_FLOAT_EQ(points[0].y(), -0.5f);
  EXPECT_FLOAT_EQ(points[0].z(), 2.0f);
  EXPECT_FLOAT_EQ(points[1].x(), -6.0f);  // (0 - 1.5) 8 / 2
  EXPECT_FLOAT_EQ(points[1].y(), 2.0f);   // (2 - 1) 8 / 4
  EXPECT_FLOAT_EQ(points[1].z(), 8.0f);
}

TEST(PeerClouds, TumDefaultsPutTheImageCentreOnTheAxis) {
  hal::cloud::DepthImage image{.width = 640, .height = 480, .depth_m = std::vector<float>(640 * 480, 0.0f)};
  image.depth_m[479 * 640 + 639] = 1.05f;  // the bottom-right pixel
  const Points points = UnprojectDepth(image, PinholeIntrinsics{}, 8.0);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_FLOAT_EQ(points[0].x(), static_cast<float>(319.5 * 1.05 / 525.0));
  EXPECT_FLOAT_EQ(points[0].y(), static_cast<float>(239.5 * 1.05 / 525.0));
}

TEST(PeerClouds, Hdl32eScanLosesExactlyItsZeroRangeReturns) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/hdl32e_fast_gicp_pair/251370668.pcd");
  const auto points = LoadPeerPoints(path, {});
  ASSERT_TRUE(points.ok()) << points.error().message;
  EXPECT_EQ(points->size(), 69088u - 5032u);  // tests/hal/cloud/cloud_real_data_test.cpp
}

TEST(PeerClouds, ErrorsNameTheFile) {
  const auto unknown = LoadPeerPoints("scan.xyz", {});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message, "scan.xyz: unknown file type (.pcd, .ply, .bin or .png)");
  const auto missing = LoadPeerPoints("/nonexistent/scan.pcd", {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/scan.pcd"), std::string::npos) << missing.error().message;
}

TEST(PeerClouds, BothLibrariesGetThePointsAsGiven) {
  const Points points = {{1.5f, -2.25f, 0.125f}, {-7, 8, 9}};
  const auto pcl_cloud = ToPcl(points);
  ASSERT_EQ(pcl_cloud->size(), 2u);
  EXPECT_TRUE(pcl_cloud->is_dense);
  EXPECT_EQ((*pcl_cloud)[1].getVector3fMap(), points[1]);
  const auto open3d_cloud = ToOpen3d(points);
  ASSERT_EQ(open3d_cloud->points_.size(), 2u);
  EXPECT_EQ(open3d_cloud->points_[0], points[0].cast<double>());
  EXPECT_FALSE(open3d_cloud->HasNormals());
}

}  // namespace
}  // namespace flat2d::localization::peers
