#include "localization/registration/nicp.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/linear_system.hpp"
#include "localization/registration/snicp.hpp"

#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "tests/testing/pose_error.hpp"

#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/neighbour_statistics.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::localization::registration {
namespace {

using maps::range3d::IndexImage;
using maps::range3d::PinholeIntrinsics;
using maps::range3d::RangeProjection;
using maps::range3d::SurfelCloud;

Eigen::Isometry3f CameraPose() {
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = world_R_optical * Eigen::AngleAxisf(0.4F, Eigen::Vector3f::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3f(-1.5F, 0.3F, 1.4F);
  return pose;
}

Eigen::Isometry3f RandomMotion(std::mt19937& rng, float max_angle_rad, float max_translation_m) {
  std::uniform_real_distribution<float> unit(-1.0F, 1.0F);
  // Braces: the draws are made in order (a call's arguments have none).
  const Eigen::Vector3f axis = Eigen::Vector3f{unit(rng), unit(rng), unit(rng)}.normalized();
  Eigen::Isometry3f motion = Eigen::Isometry3f::Identity();
  motion.linear() = Eigen::AngleAxisf(max_angle_rad * std::abs(unit(rng)), axis).toRotationMatrix();
  motion.translation() = max_translation_m * Eigen::Vector3f{unit(rng), unit(rng), unit(rng)};
  return motion;
}

SurfelCloud DepthFrame(const Eigen::Isometry3f& world_T_camera, const RangeProjection& projection) {
  std::mt19937 rng(3);
  const auto depth = testing::RenderDepth(testing::OfficeRoom(), projection.intrinsics(), world_T_camera, 0.002F, rng);
  SurfelCloud cloud;
  IndexImage image;
  maps::range3d::CloudFromDepth(depth, projection, 8.0F, cloud, image);
  maps::range3d::SurfaceStatistics(maps::range3d::SurfaceStatisticsOptions{}).Compute(projection, image, cloud);
  return cloud;
}

class NicpOnDepthFrames : public ::testing::TestWithParam<ErrorMetric> {};

TEST_P(NicpOnDepthFrames, RecoversSeededMotionsFromIdentity) {
  const RangeProjection projection = RangeProjection::Pinhole({});
  const Eigen::Isometry3f world_T_target = CameraPose();
  const SurfelCloud target = DepthFrame(world_T_target, projection);
  ProjectiveCorrespondenceFinder finder(target, projection);
  NicpOptions options;
  options.metric = GetParam();
  Nicp nicp(options);
  std::mt19937 rng(42);
  std::printf("seed 42\n");
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Isometry3f target_T_source = RandomMotion(rng, 4.0F * static_cast<float>(M_PI) / 180.0F, 0.05F);
    const SurfelCloud source = DepthFrame(world_T_target * target_T_source, projection);
    const RegistrationResult result = nicp.Register(target, finder, source, Eigen::Isometry3d::Identity());
    ASSERT_TRUE(result.ok()) << FailureName(result.failure);
    const testing::PoseError e = testing::PoseErrorOf(result.target_T_source, target_T_source.cast<double>());
    std::printf("trial %d: %.2f mm %.3f deg, %d inliers, %d iterations\n", trial, 1e3 * e.translation_m,
                e.rotation_deg, result.inliers, result.iterations);
    EXPECT_LT(e.translation_m, 0.003) << "trial " << trial;
    EXPECT_LT(e.rotation_deg, 0.1) << "trial " << trial;
    EXPECT_GT(result.inliers, 50000);
  }
}

INSTANTIATE_TEST_SUITE_P(Metrics, NicpOnDepthFrames, ::testing::Values(ErrorMetric::kNicp, ErrorMetric::kPointToPlane));

TEST(Snicp, RecoversSeededMotionsThroughThePyramid) {
  const PinholeIntrinsics intrinsics;
  const Eigen::Isometry3f world_T_target = CameraPose();
  std::mt19937 noise(3);
  auto pyramid = [&](const Eigen::Isometry3f& pose) {
    const auto depth = testing::RenderDepth(testing::OfficeRoom(), intrinsics, pose, 0.002F, noise);
    return MakeSnicpFrame(depth, maps::range3d::RangeFrameOptions{}, SnicpOptions{});
  };
  const SnicpFrame target = pyramid(world_T_target);
  ASSERT_EQ(target.levels.size(), 3U);
  EXPECT_EQ(target.levels[0].projection.cols(), 160);
  std::mt19937 rng(42);
  std::printf("seed 42\n");
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Isometry3f target_T_source = RandomMotion(rng, 4.0F * static_cast<float>(M_PI) / 180.0F, 0.05F);
    const SnicpFrame source = pyramid(world_T_target * target_T_source);
    const FrameRegistration r = RegisterSnicp(target, source, Eigen::Isometry3d::Identity(), NicpOptions{}, SnicpOptions{});
    ASSERT_TRUE(r.result.ok()) << FailureName(r.result.failure);
    EXPECT_LE(r.result.iterations, 9);  // 3 a level, fewer where a level converges
    EXPECT_GE(r.result.iterations, 3);
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, target_T_source.cast<double>());
    std::printf("snicp trial %d: %.2f mm %.3f deg\n", trial, 1e3 * e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.003) << "trial " << trial;
    EXPECT_LT(e.rotation_deg, 0.1) << "trial " << trial;
  }
}

// The pyramid is built on the frames' working resolution: at image_scale 4 (160x120, the
// real-time configuration of docs/benchmarks.md) the levels 2, 1 are 80x60 and 160x120.
TEST(Snicp, ThePyramidStandsOnTheWorkingResolution) {
  const PinholeIntrinsics intrinsics;
  const Eigen::Isometry3f world_T_target = CameraPose();
  maps::range3d::RangeFrameOptions frames;
  frames.image_scale = 4;
  SnicpOptions options;
  options.scales = {2, 1};
  std::mt19937 noise(5);
  auto pyramid = [&](const Eigen::Isometry3f& pose) {
    const auto depth = testing::RenderDepth(testing::OfficeRoom(), intrinsics, pose, 0.002F, noise);
    return MakeSnicpFrame(depth, frames, options);
  };
  const SnicpFrame target = pyramid(world_T_target);
  ASSERT_EQ(target.levels.size(), 2U);
  EXPECT_EQ(target.levels[0].projection.cols(), 80);
  EXPECT_EQ(target.levels[0].projection.rows(), 60);
  EXPECT_EQ(target.levels[1].projection.cols(), 160);
  EXPECT_FLOAT_EQ(target.levels[1].projection.intrinsics().fx, 525.0F / 4.0F);
  std::mt19937 rng(43);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Isometry3f target_T_source = RandomMotion(rng, 3.0F * static_cast<float>(M_PI) / 180.0F, 0.03F);
    const SnicpFrame source = pyramid(world_T_target * target_T_source);
    const FrameRegistration r = RegisterSnicp(target, source, Eigen::Isometry3d::Identity(), NicpOptions{}, options);
    ASSERT_TRUE(r.result.ok()) << FailureName(r.result.failure);
    EXPECT_LE(r.result.iterations, 6);  // 3 a level
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, target_T_source.cast<double>());
    std::printf("snicp at 160x120, trial %d: %.2f mm %.3f deg\n", trial, 1e3 * e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.001) << "trial " << trial;
    EXPECT_LT(e.rotation_deg, 0.02) << "trial " << trial;
  }
}

TEST(NicpOverRadii, TheLastRadiusTakesFiveIterationsTheCoarseOnesTheRest) {
  EXPECT_EQ(IterationsPerRadius(10, 1), (std::vector<int>{10}));
  EXPECT_EQ(IterationsPerRadius(10, 2), (std::vector<int>{5, 5}));
  EXPECT_EQ(IterationsPerRadius(30, 2), (std::vector<int>{25, 5}));
  EXPECT_EQ(IterationsPerRadius(7, 2), (std::vector<int>{4, 3}));
  EXPECT_EQ(IterationsPerRadius(1, 2), (std::vector<int>{1, 0}));
  EXPECT_EQ(IterationsPerRadius(10, 3), (std::vector<int>{3, 2, 5}));
  EXPECT_EQ(IterationsPerRadius(10, 0), (std::vector<int>{10}));
}

// The coarse-to-fine schedule: one radius is RegisterFrames itself; two share the
// iterations (the last radius 5 of 10, 5 of 30) and land on seeded motions.
TEST(NicpOverRadii, SharesTheIterationsAndRecoversSeededMotions) {
  const PinholeIntrinsics intrinsics;
  const Eigen::Isometry3f world_T_target = CameraPose();
  maps::range3d::RangeFrameOptions frames;
  frames.image_scale = 4;
  std::mt19937 noise(9);
  auto frame = [&](const Eigen::Isometry3f& pose) {
    return maps::range3d::FrameFromDepth(testing::RenderDepth(testing::OfficeRoom(), intrinsics, pose, 0.002F, noise),
                                         frames);
  };
  const maps::range3d::RangeFrame target = frame(world_T_target);
  std::mt19937 rng(44);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Isometry3f target_T_source = RandomMotion(rng, 3.0F * static_cast<float>(M_PI) / 180.0F, 0.03F);
    const maps::range3d::RangeFrame source = frame(world_T_target * target_T_source);
    maps::range3d::RangeFrame t1 = target, s1 = source, t2 = target, s2 = source;
    const FrameRegistration alone = RegisterFrames(target, source, Eigen::Isometry3d::Identity(),
                                                   RegistrationMethod::kNicp, NicpOptions{});
    const FrameRegistration one = RegisterFramesOverRadii(frames, {0.1F}, t1, s1, Eigen::Isometry3d::Identity(),
                                                          RegistrationMethod::kNicp, NicpOptions{});
    EXPECT_TRUE(one.result.target_T_source.isApprox(alone.result.target_T_source, 0.0));
    EXPECT_EQ(one.result.iterations, alone.result.iterations);

    NicpOptions options;
    options.iterations = 30;
    options.convergence_step = 0.0;  // run every iteration, to count them
    const FrameRegistration two = RegisterFramesOverRadii(frames, {0.1F, 0.03F}, t2, s2,
                                                          Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp,
                                                          options);
    ASSERT_TRUE(two.result.ok()) << FailureName(two.result.failure);
    EXPECT_EQ(two.result.iterations, 30);
    EXPECT_FLOAT_EQ(t2.statistics_radius_m, 0.03F);
    EXPECT_FLOAT_EQ(s2.statistics_radius_m, 0.03F);
    const testing::PoseError e = testing::PoseErrorOf(two.result.target_T_source, target_T_source.cast<double>());
    std::printf("radii 0.1, 0.03 at 160x120, trial %d: %.2f mm %.3f deg\n", trial, 1e3 * e.translation_m,
                e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.002) << "trial " << trial;
    EXPECT_LT(e.rotation_deg, 0.05) << "trial " << trial;
  }
}

TEST(Nicp, IdenticalFramesStayAtIdentityAndReportInformation) {
  const RangeProjection projection = RangeProjection::Pinhole({});
  const SurfelCloud frame = DepthFrame(CameraPose(), projection);
  ProjectiveCorrespondenceFinder finder(frame, projection);
  const RegistrationResult result = Nicp(NicpOptions{}).Register(frame, finder, frame, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(result.ok());
  const testing::PoseError e = testing::PoseErrorOf(result.target_T_source, Eigen::Isometry3d::Identity());
  EXPECT_LT(e.translation_m, 1e-5);
  EXPECT_LT(e.rotation_deg, 1e-3);
  EXPECT_TRUE(result.converged);
  // Six walls seen: every direction constrained, H positive definite.
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(result.information).eigenvalues().minCoeff(), 1.0);
}

TEST(Nicp, AFrameWithoutStructureFailsWithAReason) {
  const RangeProjection projection = RangeProjection::Pinhole({});
  const SurfelCloud target = DepthFrame(CameraPose(), projection);
  ProjectiveCorrespondenceFinder finder(target, projection);
  SurfelCloud empty;
  empty.Resize(0);
  const RegistrationResult result = Nicp(NicpOptions{}).Register(target, finder, empty, Eigen::Isometry3d::Identity());
  EXPECT_EQ(result.failure, RegistrationFailure::kTooFewCorrespondences);
  EXPECT_EQ(result.iterations, 1);
}

TEST(Nicp, KdTreeModeAlignsUnorganizedClouds) {
  const RangeProjection projection = RangeProjection::Pinhole({160, 120, 131.25F, 131.25F, 79.5F, 59.5F});
  std::mt19937 rng(11);
  const Eigen::Isometry3f world_T_target = CameraPose();
  const Eigen::Isometry3f target_T_source = RandomMotion(rng, 3.0F * static_cast<float>(M_PI) / 180.0F, 0.04F);
  auto unorganized = [&](const Eigen::Isometry3f& pose) {
    std::mt19937 noise(5);
    const auto depth = testing::RenderDepth(testing::OfficeRoom(), projection.intrinsics(), pose, 0.0F, noise);
    SurfelCloud cloud;
    IndexImage image;
    maps::range3d::CloudFromDepth(depth, projection, 8.0F, cloud, image);
    maps::range3d::ComputeNeighbourStatistics(maps::range3d::SurfaceStatisticsOptions{}, Eigen::Vector3f::Zero(), cloud);
    return cloud;
  };
  const SurfelCloud target = unorganized(world_T_target);
  const SurfelCloud source = unorganized(world_T_target * target_T_source);
  NicpOptions options;
  options.iterations = 30;
  KdTreeCorrespondenceFinder finder(target, options.kdtree_alpha);
  const RegistrationResult result = Nicp(options).Register(target, finder, source, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(result.ok());
  const testing::PoseError e = testing::PoseErrorOf(result.target_T_source, target_T_source.cast<double>());
  std::printf("kd-tree: %.2f mm %.3f deg, %d iterations\n", 1e3 * e.translation_m, e.rotation_deg, result.iterations);
  EXPECT_LT(e.translation_m, 0.01);
  EXPECT_LT(e.rotation_deg, 0.3);
}

}  // namespace
}  // namespace flat2d::localization::registration
