// The real 3D captures of ../shared/data (PROVENANCE.md, section "3D LiDAR / depth
// registration data helper"; lidar3d/README.md, depth/README.md): point counts, the
// HDL-32E zero-range returns, VLP-16 rings, the Stanford bunny's range grid, a KITTI
// scan and a TUM depth frame, with values checked independently of these readers.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/pcd_file.hpp"
#include "hal/cloud/ply_file.hpp"
#include "hal/cloud/tum_depth_png.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::cloud {
namespace {

TEST(CloudRealData, Hdl32ePcdHasItsPointsAndZeroRangeReturns) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/hdl32e_fast_gicp_pair/251370668.pcd");
  const Result<PointCloud> cloud = ReadPcd(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 69088u);  // 32 lasers x 2159 firings
  ASSERT_EQ(cloud->intensity.size(), 69088u);
  EXPECT_TRUE(cloud->ring.empty());  // the ring is implicit (index % 32), no field
  EXPECT_FALSE(cloud->organized());  // HEIGHT 1
  std::size_t zero_range = 0;
  for (const Eigen::Vector3f& p : cloud->points) zero_range += p.isZero(0.0f) ? 1 : 0;
  EXPECT_EQ(zero_range, 5032u);
  EXPECT_FLOAT_EQ(cloud->points[0].y(), 2.570035f);
  EXPECT_FLOAT_EQ(cloud->points[0].z(), -1.5241568f);
  EXPECT_EQ(cloud->intensity[0], 68.0f);
  EXPECT_EQ(*std::max_element(cloud->intensity.begin(), cloud->intensity.end()), 215.0f);
}

TEST(CloudRealData, Vlp16PcdsKeepTheRingField) {
  // Fields x y z intensity ring(U2) azimuth distance return_type(U1) time_stamp(F8): 35-byte
  // records, and WIDTH 0 HEIGHT 0 in the header.
  FLAT2D_REQUIRE_DATA(path, "lidar3d/vlp16_nebula_indoor/1673400472138016708.pcd");
  const Result<PointCloud> cloud = ReadPcd(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 14673u);
  ASSERT_EQ(cloud->ring.size(), 14673u);
  std::map<int, int> per_ring;
  float max_range = 0.0f;
  for (std::size_t i = 0; i < cloud->points.size(); ++i) {
    ++per_ring[cloud->ring[i]];
    max_range = std::max(max_range, cloud->points[i].norm());
  }
  EXPECT_EQ(per_ring.size(), 15u);  // ring 0 (-15 deg) saw nothing in this room
  EXPECT_EQ(per_ring.begin()->first, 1);
  EXPECT_EQ(per_ring.rbegin()->first, 15);
  EXPECT_EQ(per_ring[1], 18);
  EXPECT_EQ(per_ring[15], 1495);
  EXPECT_NEAR(max_range, 14.624f, 1e-3f);
  EXPECT_EQ(cloud->ring[0], 8);
  EXPECT_FLOAT_EQ(cloud->points[0].x(), 0.96079367f);
  EXPECT_EQ(cloud->intensity[0], 100.0f);
  EXPECT_EQ(cloud->intensity.back(), 25.0f);
}

TEST(CloudRealData, EveryVlp16SweepReads) {
  const std::pair<const char*, std::size_t> sweeps[] = {
      {"1673400472238200562", 14818}, {"1673400472338327770", 14916},
      {"1673400472437610688", 14672}, {"1673400472537996703", 14820}};
  for (const auto& [name, points] : sweeps) {
    FLAT2D_REQUIRE_DATA(path, std::string("lidar3d/vlp16_nebula_indoor/") + name + ".pcd");
    const Result<PointCloud> cloud = ReadPcd(path);
    ASSERT_TRUE(cloud.ok()) << cloud.error().message;
    EXPECT_EQ(cloud->points.size(), points) << name;
  }
}

TEST(CloudRealData, StanfordBunnyScanIsA512By400RangeGrid) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/stanford_bunny_scans/bun000.ply");
  const Result<PointCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 40256u);
  EXPECT_TRUE(cloud->intensity.empty());
  ASSERT_EQ(cloud->grid_width, 512);
  ASSERT_EQ(cloud->grid_height, 400);
  ASSERT_EQ(cloud->grid.size(), 204800u);
  // Every vertex sits in exactly one cell, in file order: cell order is vertex order.
  std::int32_t previous = -1;
  std::size_t filled = 0;
  for (const std::int32_t cell : cloud->grid) {
    if (cell < 0) continue;
    ASSERT_EQ(cell, previous + 1);
    previous = cell;
    ++filled;
  }
  EXPECT_EQ(filled, 40256u);
  EXPECT_EQ(cloud->grid[27 * 512 + 128], 0);  // first filled cell: row 27, column 128
  EXPECT_EQ(cloud->grid[240 * 512 + 219], 40255);
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(-0.06325f, 0.0359793f, 0.0420873f));
  EXPECT_EQ(cloud->points[40255], Eigen::Vector3f(-0.018f, 0.18794f, -0.0197253f));
  // File row order: row 0 is the scan's lowest y (the bunny stands y-up), so rows grow
  // upwards, and x grows with the column.
  const Eigen::Vector3f low = cloud->points[static_cast<std::size_t>(cloud->grid[27 * 512 + 128])];
  const Eigen::Vector3f high = cloud->points[static_cast<std::size_t>(cloud->grid[240 * 512 + 219])];
  EXPECT_LT(low.y(), high.y());
  EXPECT_LT(low.x(), high.x());
}

TEST(CloudRealData, EveryBunnyScanFillsOneCellPerVertex) {
  const std::pair<const char*, std::size_t> scans[] = {
      {"bun045", 40097}, {"bun090", 30379}, {"bun180", 40251}, {"bun270", 31701}, {"bun315", 35336}};
  for (const auto& [name, vertices] : scans) {
    FLAT2D_REQUIRE_DATA(path, std::string("lidar3d/stanford_bunny_scans/") + name + ".ply");
    const Result<PointCloud> cloud = ReadPly(path);
    ASSERT_TRUE(cloud.ok()) << cloud.error().message;
    EXPECT_EQ(cloud->points.size(), vertices) << name;
    EXPECT_EQ(cloud->grid.size(), 512u * 400u) << name;
    EXPECT_EQ(static_cast<std::size_t>(std::count_if(cloud->grid.begin(), cloud->grid.end(),
                                                     [](std::int32_t cell) { return cell >= 0; })),
              vertices)
        << name;
  }
}

TEST(CloudRealData, StanfordBunnyMeshKeepsIntensityAndSkipsFaces) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/stanford_bunny_scans/bun_zipper.ply");
  const Result<PointCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 35947u);
  ASSERT_EQ(cloud->intensity.size(), 35947u);
  EXPECT_FALSE(cloud->organized());
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(-0.0378297f, 0.12794f, 0.00447467f));
  EXPECT_EQ(cloud->points.back(), Eigen::Vector3f(-0.0400442f, 0.15362f, -0.00816685f));
  EXPECT_EQ(cloud->intensity[0], 0.5f);
  EXPECT_EQ(cloud->intensity[35944], 0.337855f);  // the 5th column, not the 4th (confidence)
  EXPECT_EQ(std::count_if(cloud->intensity.begin(), cloud->intensity.end(), [](float i) { return i != 0.5f; }), 7719);
}

TEST(CloudRealData, KittiScanHasItsPoints) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/kitti_odometry_00_frames_000000-000015/velodyne/000000.bin");
  const Result<PointCloud> cloud = ReadKittiBin(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 124668u);
  EXPECT_FLOAT_EQ(cloud->points[0].x(), 52.897942f);
  EXPECT_FLOAT_EQ(cloud->intensity[0], 0.08f);
  EXPECT_FLOAT_EQ(cloud->points.back().z(), -1.895561f);
  for (const float r : cloud->intensity) ASSERT_TRUE(r >= 0.0f && r <= 1.0f) << r;
}

TEST(CloudRealData, TumDepthFrameIs640By480Metres) {
  FLAT2D_REQUIRE_DATA(list, "depth/tum_rgbd_fr1_rpy_first200/depth.txt");
  const Result<std::vector<DepthFrame>> frames = ReadTumAssociationList(list);
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  ASSERT_EQ(frames->size(), 200u);
  EXPECT_DOUBLE_EQ(frames->front().time_s, 1305031229.528784);
  EXPECT_DOUBLE_EQ(frames->back().time_s, 1305031236.170933);
  EXPECT_EQ(frames->front().file, list.parent_path() / "depth" / "1305031229.528784.png");
  const Result<DepthImage> image = ReadTumDepthPng(frames->front().file);
  ASSERT_TRUE(image.ok()) << image.error().message;
  ASSERT_EQ(image->width, 640);
  ASSERT_EQ(image->height, 480);
  // Decoded independently (zlib + PNG filters): raw 6192 at the centre, 5815 at (0, 0).
  EXPECT_FLOAT_EQ(image->at(240, 320), 6192.0f / 5000.0f);
  EXPECT_FLOAT_EQ(image->at(0, 0), 5815.0f / 5000.0f);
  EXPECT_EQ(image->at(100, 200), 0.0f);
  const auto zeros = std::count(image->depth_m.begin(), image->depth_m.end(), 0.0f);
  EXPECT_EQ(zeros, 89238);
  float lo = 1e9f, hi = 0.0f;
  for (const float d : image->depth_m) {
    if (d == 0.0f) continue;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  EXPECT_FLOAT_EQ(lo, 3679.0f / 5000.0f);
  EXPECT_FLOAT_EQ(hi, 14069.0f / 5000.0f);
}

}  // namespace
}  // namespace flat2d::hal::cloud
