#include "maps/range3d/range_frame.hpp"

#include <random>

#include <gtest/gtest.h>

#include "tests/testing/box_scene.hpp"

namespace flat2d::maps::range3d {
namespace {

// The office room seen from 1.5 m up, looking along +x, with 5 mm of depth noise so that
// the radius of the fit shows in the normals.
hal::cloud::DepthImage NoisyOfficeDepth() {
  Eigen::Isometry3f camera = Eigen::Isometry3f::Identity();
  camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // optical z = world x
  camera.translation() = Eigen::Vector3f(-1.0F, 0.0F, 1.5F);
  std::mt19937 rng(11);
  return testing::RenderDepth(testing::OfficeRoom(), PinholeIntrinsics{}, camera, 0.005F, rng);
}

RangeFrameOptions OptionsWithRadius(float radius_m) {
  RangeFrameOptions options;
  options.image_scale = 2;
  options.depth_statistics.radius_m = radius_m;
  // At 0.03 m the far wall (4 m away, 2 px a side at 320x240) has 25 points in its
  // rectangle, so there the small radius leaves normals undefined that the wide one had.
  options.depth_statistics.min_points = 30;
  return options;
}

// RefitStatistics must leave nothing of the first fit behind: a refit frame is the frame
// fitted at the new radius from the start, normal for normal, defined or not.
TEST(RangeFrame, RefitOverAnotherRadiusEqualsAFreshFit) {
  const hal::cloud::DepthImage depth = NoisyOfficeDepth();
  RangeFrame refit = FrameFromDepth(depth, OptionsWithRadius(0.1F));
  const RangeFrame wide = refit;
  const RangeFrame fresh = FrameFromDepth(depth, OptionsWithRadius(0.03F));
  RefitStatistics(OptionsWithRadius(0.1F), 0.03F, refit);

  EXPECT_FLOAT_EQ(refit.statistics_radius_m, 0.03F);
  ASSERT_EQ(refit.cloud.size(), fresh.cloud.size());
  int differ_from_wide = 0, undefined_after = 0;
  for (std::size_t i = 0; i < fresh.cloud.size(); ++i) {
    ASSERT_EQ(refit.cloud.has_normal(i), fresh.cloud.has_normal(i)) << i;
    EXPECT_EQ(refit.cloud.points[i], wide.cloud.points[i]) << i;
    if (!fresh.cloud.has_normal(i)) {
      undefined_after += wide.cloud.has_normal(i) ? 1 : 0;
      continue;
    }
    EXPECT_EQ(refit.cloud.normals[i], fresh.cloud.normals[i]) << i;
    EXPECT_EQ(refit.cloud.curvature[i], fresh.cloud.curvature[i]) << i;
    EXPECT_EQ(refit.cloud.disc_gain[i], fresh.cloud.disc_gain[i]) << i;
    differ_from_wide += (wide.cloud.normals[i] - fresh.cloud.normals[i]).norm() > 1e-3F ? 1 : 0;
  }
  // The two radii do give different normals (else the test shows nothing), and the small
  // one leaves some points without enough neighbours, which the refit must not keep.
  EXPECT_GT(differ_from_wide, 1000);
  EXPECT_GT(undefined_after, 0);
}

}  // namespace
}  // namespace flat2d::maps::range3d
