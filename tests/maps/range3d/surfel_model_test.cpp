#include "maps/range3d/surfel_model.hpp"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::maps::range3d {
namespace {

Eigen::Isometry3f CameraPose() {  // looking along +x at the far wall, from inside the room
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = world_R_optical;
  pose.translation() = Eigen::Vector3f(-2.5F, 0.0F, 1.4F);
  return pose;
}

struct ModelFrame {
  SurfelCloud cloud;
  IndexImage image;
};

ModelFrame Render(const testing::BoxScene& scene, const RangeProjection& projection, float noise_m, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const auto depth = testing::RenderDepth(scene, projection.intrinsics(), CameraPose(), noise_m, rng);
  ModelFrame frame;
  CloudFromDepth(depth, projection, 8.0F, frame.cloud, frame.image);
  SurfaceStatistics(SurfaceStatisticsOptions{}).Compute(projection, frame.image, frame.cloud);
  return frame;
}

std::size_t WithNormal(const SurfelCloud& cloud) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) n += cloud.has_normal(i) ? 1 : 0;
  return n;
}

// A 320 x 240 camera keeps the test fast; the merging does not care about the size.
RangeProjection SmallCamera() { return RangeProjection::Pinhole({320, 240, 262.5F, 262.5F, 159.5F, 119.5F}); }

TEST(SurfelModel, TheSameFrameTwiceMergesPointForPoint) {
  const RangeProjection projection = SmallCamera();
  const ModelFrame frame = Render(testing::OfficeRoom(), projection, 0.0F, 1);
  SurfelModel model{SurfelModelOptions{}};
  const MergeStats first = model.Merge(frame.cloud, frame.image, projection, CameraPose());
  EXPECT_EQ(first.added, WithNormal(frame.cloud));
  EXPECT_EQ(first.merged, 0U);
  const MergeStats second = model.Merge(frame.cloud, frame.image, projection, CameraPose());
  std::printf("%zu points, second merge: %zu merged, %zu replaced, %zu added\n", model.size(), second.merged,
              second.replaced, second.added);
  EXPECT_EQ(second.replaced, 0U);
  // Every model point lands on its own pixel: one cluster each, the model does not grow.
  EXPECT_GE(second.merged, first.added * 99 / 100);
  EXPECT_LE(model.size(), first.added + first.added / 100);
  for (const float w : model.weights()) EXPECT_LE(w, SurfelModelOptions{}.max_weight);
}

// A first merge writes each point with its measurement's weight: 1 / depth^2 for a depth
// camera (Eq. 5.22), 1 / depth for LiDAR local maps (Eq. 6.4).
TEST(SurfelModel, AMeasurementWeighsByItsDepth) {
  const RangeProjection projection = SmallCamera();
  const ModelFrame frame = Render(testing::OfficeRoom(), projection, 0.0F, 1);
  for (const DepthWeighting weighting : {DepthWeighting::kInverseSquare, DepthWeighting::kInverse}) {
    SurfelModelOptions options;
    options.weighting = weighting;
    SurfelModel model{options};
    model.Merge(frame.cloud, frame.image, projection, CameraPose());
    ASSERT_GT(model.size(), 1000U);
    const Eigen::Isometry3f camera_T_model = CameraPose().inverse();
    for (std::size_t i = 0; i < model.size(); i += 97) {
      const float depth = (camera_T_model * model.cloud().points[i]).z();
      const float expected = weighting == DepthWeighting::kInverse ? 1.0F / depth : 1.0F / (depth * depth);
      ASSERT_NEAR(model.weights()[i], expected, 1e-4F * expected) << "point " << i << " at " << depth << " m";
    }
  }
}

TEST(SurfelModel, ARemovedObjectIsSeenThroughAndItsWallKeptBehindAnAddedOne) {
  const RangeProjection projection = SmallCamera();
  testing::BoxScene empty = testing::OfficeRoom();
  empty.furniture.clear();
  const ModelFrame furnished = Render(testing::OfficeRoom(), projection, 0.0F, 1);
  const ModelFrame bare = Render(empty, projection, 0.0F, 1);

  // The furniture leaves: the bare room's beams pass through its points.
  SurfelModel leaving{SurfelModelOptions{}};
  (void)leaving.Merge(furnished.cloud, furnished.image, projection, CameraPose());
  const MergeStats left = leaving.Merge(bare.cloud, bare.image, projection, CameraPose());
  std::printf("furniture leaves: %zu replaced, %zu merged; furniture arrives: ", left.replaced, left.merged);
  EXPECT_GT(left.replaced, 1000U);
  // A furniture face: on a box, and more than 10 cm from the room's floor, walls and
  // ceiling (where a face meets them, the surface behind is within tau: one cluster, or
  // kept for its normal).
  const testing::BoxScene room = testing::OfficeRoom();
  auto on_room = [&](const Eigen::Vector3f& p) {
    return ((p - room.room.min).array().abs() < 0.1F).any() || ((p - room.room.max).array().abs() < 0.1F).any();
  };
  std::size_t on_furniture = 0;
  for (const Eigen::Vector3f& p : leaving.cloud().points) {
    for (const testing::AxisBox& box : room.furniture) {
      const bool inside = ((p.array() >= box.min.array() - 0.02F) && (p.array() <= box.max.array() + 0.02F)).all();
      on_furniture += inside && !on_room(p) ? 1 : 0;
    }
  }
  EXPECT_EQ(on_furniture, 0U) << "points of the furniture survived its removal";

  // The furniture arrives: the walls behind it are occluded, not removed.
  SurfelModel arriving{SurfelModelOptions{}};
  (void)arriving.Merge(bare.cloud, bare.image, projection, CameraPose());
  const MergeStats arrived = arriving.Merge(furnished.cloud, furnished.image, projection, CameraPose());
  std::printf("%zu replaced, %zu merged, model %zu\n", arrived.replaced, arrived.merged, arriving.size());
  EXPECT_EQ(arrived.replaced, 0U);
  EXPECT_GT(arriving.size(), WithNormal(furnished.cloud) + 1000);  // the hidden wall is still there
}

TEST(SurfelModel, MergingNoisyFramesAveragesTheNoiseDown) {
  const RangeProjection projection = SmallCamera();
  const double sigma = 0.005;
  SurfelModel model{SurfelModelOptions{}};
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    const ModelFrame frame = Render(testing::OfficeRoom(), projection, static_cast<float>(sigma), seed);
    (void)model.Merge(frame.cloud, frame.image, projection, CameraPose());
  }
  // The far wall is x = room.max.x: the spread of the points on it, normal to the wall.
  const float wall_x = testing::OfficeRoom().room.max.x();
  double sum = 0.0;
  std::size_t n = 0;
  for (const Eigen::Vector3f& p : model.cloud().points) {
    if (std::abs(p.x() - wall_x) > 0.05F || std::abs(p.y()) > 1.0F) continue;
    const double off = static_cast<double>(p.x() - wall_x);
    sum += off * off;
    ++n;
  }
  ASSERT_GT(n, 1000U);
  const double rms = std::sqrt(sum / static_cast<double>(n));
  std::printf("wall rms after 10 frames of %.1f mm noise: %.2f mm over %zu points\n", 1e3 * sigma, 1e3 * rms, n);
  EXPECT_LT(rms, 0.5 * sigma);  // 10 frames: sqrt(10) less in theory
}

TEST(SurfelModel, StaysWithinItsPointBudgetDroppingTheOldest) {
  const RangeProjection projection = SmallCamera();
  SurfelModelOptions options;
  options.max_points = 20000;
  SurfelModel model(options);
  const ModelFrame frame = Render(testing::OfficeRoom(), projection, 0.0F, 1);
  const MergeStats stats = model.Merge(frame.cloud, frame.image, projection, CameraPose());
  EXPECT_EQ(model.size(), 20000U);
  EXPECT_EQ(stats.dropped, stats.added - 20000U);
}

TEST(SurfelModel, RendersWhatTheCameraSeesInItsOwnFrame) {
  const RangeProjection projection = SmallCamera();
  const ModelFrame frame = Render(testing::OfficeRoom(), projection, 0.0F, 1);
  SurfelModel model{SurfelModelOptions{}};
  (void)model.Merge(frame.cloud, frame.image, projection, CameraPose());
  SurfelCloud view;
  IndexImage image;
  model.Render(projection, CameraPose(), view, image);
  EXPECT_GE(view.size(), WithNormal(frame.cloud) * 99 / 100);
  // A pixel of the view shows, in the camera frame, the point the frame measured there.
  int compared = 0;
  for (int row = 0; row < image.rows(); row += 7) {
    for (int col = 0; col < image.cols(); col += 7) {
      const std::int32_t v = image.at(row, col), f = frame.image.at(row, col);
      if (v < 0 || f < 0 || !frame.cloud.has_normal(static_cast<std::size_t>(f))) continue;
      EXPECT_LT((view.points[static_cast<std::size_t>(v)] - frame.cloud.points[static_cast<std::size_t>(f)]).norm(), 1e-4F);
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace flat2d::maps::range3d
