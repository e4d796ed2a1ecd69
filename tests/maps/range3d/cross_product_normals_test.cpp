#include "maps/range3d/cross_product_normals.hpp"

#include <random>

#include <gtest/gtest.h>

#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::maps::range3d {
namespace {

struct RoomFrame {
  SurfelCloud cloud;
  IndexImage image;
};

// The office room from 1.5 m up, looking along +x at the far wall (x = 3 m).
RoomFrame RenderRoomFrame(float sigma_m) {
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = world_R_optical;
  pose.translation() = Eigen::Vector3f(-1.0F, 0.0F, 1.5F);
  std::mt19937 rng(7);
  const PinholeIntrinsics intrinsics;
  const auto depth = testing::RenderDepth(testing::OfficeRoom(), intrinsics, pose, sigma_m, rng);
  RoomFrame frame;
  CloudFromDepth(depth, RangeProjection::Pinhole(intrinsics), 10.0F, frame.cloud, frame.image);
  return frame;
}

TEST(CrossProductNormals, AWallsNormalIsExactAndFlat) {
  RoomFrame frame = RenderRoomFrame(0.0F);
  CrossProductNormals(CrossProductNormalOptions{}).Compute(frame.image, frame.cloud);
  const auto index = static_cast<std::size_t>(frame.image.at(240, 320));
  ASSERT_TRUE(frame.cloud.has_normal(index));
  EXPECT_NEAR(frame.cloud.normals[index].z(), -1.0F, 1e-5F);  // faces the camera
  EXPECT_LT(frame.cloud.curvature[index], 1e-5F);
  EXPECT_GT(frame.cloud.disc_gain[index], 998.0F);
}

TEST(CrossProductNormals, AgreeWithTheEigenNormalsOnNoisyWalls) {
  RoomFrame fast = RenderRoomFrame(0.003F);
  RoomFrame exact = fast;
  CrossProductNormals(CrossProductNormalOptions{}).Compute(fast.image, fast.cloud);
  SurfaceStatistics(SurfaceStatisticsOptions{}).Compute(RangeProjection::Pinhole({}), exact.image, exact.cloud);
  int compared = 0, agreeing = 0;
  for (std::size_t i = 0; i < fast.cloud.size(); i += 13) {
    if (!fast.cloud.has_normal(i) || !exact.cloud.has_normal(i)) continue;
    ++compared;
    agreeing += fast.cloud.normals[i].dot(exact.cloud.normals[i]) > 0.95F ? 1 : 0;  // Eq. 5.8's test
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(agreeing, compared * 9 / 10) << agreeing << " of " << compared;
}

TEST(CrossProductNormals, NoNormalAcrossADepthJumpOrAHole) {
  RoomFrame frame = RenderRoomFrame(0.0F);
  // Punch a hole: pixels with no point around (240, 320).
  for (int row = 238; row <= 242; ++row) {
    for (int col = 318; col <= 322; ++col) frame.image.Set(row, col, -1, std::numeric_limits<float>::infinity());
  }
  CrossProductNormals(CrossProductNormalOptions{}).Compute(frame.image, frame.cloud);
  // Two pixels left of the hole, the right neighbour (delta 2) is missing: no raw normal.
  const auto beside = static_cast<std::size_t>(frame.image.at(240, 316));
  EXPECT_FALSE(frame.cloud.has_normal(beside));
}

}  // namespace
}  // namespace flat2d::maps::range3d
