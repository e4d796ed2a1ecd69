#include "maps/range3d/surface_statistics.hpp"

#include <random>

#include <gtest/gtest.h>

#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/neighbour_statistics.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::maps::range3d {
namespace {

// A camera 1.5 m up in the office room, looking along +x at the far wall (x = 3 m).
Eigen::Isometry3f CameraLookingAlongX() {
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // optical z = world x, x = -world y, y = -world z
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = world_R_optical;
  pose.translation() = Eigen::Vector3f(-1.0F, 0.0F, 1.5F);
  return pose;
}

struct Frame {
  SurfelCloud cloud;
  IndexImage image;
};

Frame RenderFrame(float sigma_m) {
  std::mt19937 rng(7);
  const PinholeIntrinsics intrinsics;
  const RangeProjection projection = RangeProjection::Pinhole(intrinsics);
  const auto depth = testing::RenderDepth(testing::OfficeRoom(), intrinsics, CameraLookingAlongX(), sigma_m, rng);
  Frame frame;
  CloudFromDepth(depth, projection, 10.0F, frame.cloud, frame.image);
  SurfaceStatistics(SurfaceStatisticsOptions{}).Compute(projection, frame.image, frame.cloud);
  return frame;
}

TEST(SurfaceStatistics, WallNormalFacesTheCameraAndIsFlat) {
  const Frame frame = RenderFrame(0.0F);
  // The image centre sees the far wall x = 3 m: normal -x in the world = -z optical.
  const auto index = static_cast<std::size_t>(frame.image.at(240, 320));
  ASSERT_TRUE(frame.cloud.has_normal(index));
  EXPECT_NEAR(frame.cloud.points[index].z(), 4.0F, 1e-3F);
  EXPECT_NEAR(frame.cloud.normals[index].z(), -1.0F, 1e-4F);
  EXPECT_LT(frame.cloud.curvature[index], 1e-4F);
  // Disc information (Eq. 5.2 inverted): 1000 along the normal, 1 across.
  const Eigen::Vector3f n = frame.cloud.normals[index];
  EXPECT_NEAR(n.dot(frame.cloud.Information(index) * n), 1000.0F, 1.0F);
  EXPECT_NEAR(Eigen::Vector3f::UnitX().dot(frame.cloud.Information(index) * Eigen::Vector3f::UnitX()), 1.0F, 0.05F);
}

TEST(SurfaceStatistics, NoisyWallsStillGiveTheirNormals) {
  const Frame frame = RenderFrame(0.005F);
  int flat = 0, checked = 0;
  for (int row = 200; row < 280; row += 4) {
    for (int col = 280; col < 360; col += 4) {
      const auto index = static_cast<std::size_t>(frame.image.at(row, col));
      if (!frame.cloud.has_normal(index)) continue;
      ++checked;
      EXPECT_GT(-frame.cloud.normals[index].z(), 0.99F) << row << "," << col;
      flat += frame.cloud.curvature[index] < 0.02F ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 350);
  EXPECT_GT(flat, checked * 9 / 10);
}

TEST(SurfaceStatistics, CornersAreCurvedAndDepthJumpsDoNotBleed) {
  const Frame frame = RenderFrame(0.0F);
  int curved = 0, bled = 0, seen = 0;
  for (std::size_t i = 0; i < frame.cloud.size(); ++i) {
    if (!frame.cloud.has_normal(i)) continue;
    ++seen;
    curved += frame.cloud.curvature[i] > 0.05F ? 1 : 0;
    // Every surface of the room is axis-aligned: a normal that is not means a
    // neighbourhood that mixed two surfaces across a jump or a crease.
    const Eigen::Vector3f n = frame.cloud.normals[i].cwiseAbs();
    bled += n.maxCoeff() < 0.9F ? 1 : 0;
  }
  EXPECT_GT(seen, 250000);
  EXPECT_GT(curved, 0);                 // the creases are there...
  EXPECT_LT(bled, seen / 20);           // ...but only a thin band around them
}

TEST(NeighbourStatistics, AgreesWithTheIntegralImageOnAWall) {
  Frame frame = RenderFrame(0.0F);
  SurfelCloud unorganized;
  unorganized.Resize(0);
  for (int row = 220; row < 260; ++row) {
    for (int col = 300; col < 340; ++col) unorganized.points.push_back(frame.cloud.points[static_cast<std::size_t>(frame.image.at(row, col))]);
  }
  const auto points = unorganized.points;
  unorganized.Resize(points.size());
  unorganized.points = points;
  SurfaceStatisticsOptions options;
  options.radius_m = 0.05F;
  ComputeNeighbourStatistics(options, Eigen::Vector3f::Zero(), unorganized);
  for (std::size_t i = 0; i < unorganized.size(); ++i) {
    ASSERT_TRUE(unorganized.has_normal(i));
    EXPECT_NEAR(unorganized.normals[i].z(), -1.0F, 1e-4F);
  }
}

}  // namespace
}  // namespace flat2d::maps::range3d
