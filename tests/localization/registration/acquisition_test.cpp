// The acquisition stage (frame_registration.hpp): from a guess turned 35 deg off, an
// HDL-32E revolution in the office room is beyond the thesis' projective stages and
// within reach of KD-tree pairs with opened gates.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "localization/registration/frame_registration.hpp"
#include "tests/testing/box_scene.hpp"
#include "tests/testing/pose_error.hpp"

namespace flat2d::localization::registration {
namespace {

constexpr float kAcquisitionRadiusM = 0.3F;  // the LiDAR's first radius (RangeFrameOptions)

struct FarGuessPair {
  maps::range3d::RangeFrameOptions frames;
  maps::range3d::RangeFrame target, source;
  Eigen::Isometry3d truth;  // target_T_source
  Eigen::Isometry3d guess;  // the truth turned 35 deg about a tilted axis and shifted 0.3 m
};

FarGuessPair MakeFarGuessPair() {
  FarGuessPair pair;
  pair.frames.lidar_columns = 1080;
  Eigen::Isometry3f world_T_target = Eigen::Isometry3f::Identity();
  world_T_target.translation() = Eigen::Vector3f(-1.0F, -0.5F, 1.2F);
  Eigen::Isometry3f target_T_source = Eigen::Isometry3f::Identity();
  target_T_source.linear() = Eigen::AngleAxisf(0.05F, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  target_T_source.translation() = Eigen::Vector3f(0.15F, 0.05F, 0.0F);
  constexpr auto kHdl32e = maps::range3d::SensorModel::kHdl32e;
  pair.target = testing::RenderLidarFrame(testing::OfficeRoom(), kHdl32e, world_T_target, pair.frames);
  pair.source = testing::RenderLidarFrame(testing::OfficeRoom(), kHdl32e, world_T_target * target_T_source, pair.frames);
  pair.truth = target_T_source.cast<double>();
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.linear() = Eigen::AngleAxisd(35.0 * M_PI / 180.0, Eigen::Vector3d(0.3, -0.4, 1.0).normalized()).toRotationMatrix();
  off.translation() = Eigen::Vector3d(0.2, -0.2, 0.1);
  pair.guess = off * pair.truth;
  return pair;
}

// `pair` by value: the stages refit both frames' statistics in place.
FrameRegistration RegisterFrom(FarGuessPair pair, const Eigen::Isometry3d& guess, RegistrationMethod method,
                               const AcquisitionOptions& acquisition) {
  return RegisterFramesOverRadii(pair.frames, {kAcquisitionRadiusM, kLidarFineRadiusM}, pair.target, pair.source,
                                 guess, method, NicpOptions{}, CorrespondenceMode::kAuto, acquisition);
}

TEST(Acquisition, BringsAFarGuessWithinTheProjectiveStagesReach) {
  const FarGuessPair pair = MakeFarGuessPair();
  ASSERT_TRUE(pair.target.organized());
  const FrameRegistration thesis = RegisterFrom(pair, pair.guess, RegistrationMethod::kNicp, AcquisitionOptions{});
  const testing::PoseError stuck = testing::PoseErrorOf(thesis.result.target_T_source, pair.truth);
  AcquisitionOptions acquisition;
  acquisition.iterations = 20;
  const FrameRegistration acquired = RegisterFrom(pair, pair.guess, RegistrationMethod::kNicp, acquisition);
  ASSERT_TRUE(acquired.result.ok()) << FailureName(acquired.result.failure);
  const testing::PoseError e = testing::PoseErrorOf(acquired.result.target_T_source, pair.truth);
  std::printf("35 deg off: projective stages alone %s, %.3f m %.2f deg; acquired %.2f mm %.3f deg, %d iterations\n",
              FailureName(thesis.result.failure), stuck.translation_m, stuck.rotation_deg, 1e3 * e.translation_m,
              e.rotation_deg, acquired.result.iterations);
  EXPECT_TRUE(!thesis.result.ok() || stuck.rotation_deg > 1.0);  // the thesis' stages cannot reach it
  EXPECT_LT(e.translation_m, 0.005);
  EXPECT_LT(e.rotation_deg, 0.1);
  EXPECT_GT(acquired.result.iterations, 10);  // the acquisition's on top of the stages' 10
  EXPECT_LE(acquired.result.iterations, 30);
}

// An acquisition that finds too few pairs leaves the stages to start from the guess: the
// result is theirs alone, its iteration count the acquisition's one iteration more.
TEST(Acquisition, AFailedAcquisitionLeavesTheGuessToTheStages) {
  const FarGuessPair pair = MakeFarGuessPair();
  Eigen::Isometry3d near = pair.truth;
  near.translation() += Eigen::Vector3d(0.02, 0.0, 0.0);
  AcquisitionOptions blind;
  blind.iterations = 20;
  blind.max_distance_m = 1e-6F;  // no pair passes
  const FrameRegistration alone = RegisterFrom(pair, near, RegistrationMethod::kNicp, AcquisitionOptions{});
  const FrameRegistration after = RegisterFrom(pair, near, RegistrationMethod::kNicp, blind);
  ASSERT_TRUE(alone.result.ok());
  ASSERT_TRUE(after.result.ok());
  EXPECT_TRUE(after.result.target_T_source.isApprox(alone.result.target_T_source, 0.0));
  EXPECT_EQ(after.result.iterations, alone.result.iterations + 1);
}

TEST(Acquisition, AloneItReportsItsKdTreeAndStopsWhenFewPairsPass) {
  const FarGuessPair pair = MakeFarGuessPair();
  AcquisitionOptions acquisition;
  acquisition.iterations = 20;
  const FrameRegistration wide = Acquire(pair.target, pair.source, pair.guess, RegistrationMethod::kPointToPlane,
                                         NicpOptions{}, acquisition);
  EXPECT_TRUE(wide.kdtree);
  EXPECT_TRUE(wide.result.ok()) << FailureName(wide.result.failure);
  acquisition.max_distance_m = 1e-6F;
  const FrameRegistration blind = Acquire(pair.target, pair.source, pair.guess, RegistrationMethod::kPointToPlane,
                                          NicpOptions{}, acquisition);
  EXPECT_EQ(blind.result.failure, RegistrationFailure::kTooFewCorrespondences);
  EXPECT_EQ(blind.result.iterations, 1);
}

}  // namespace
}  // namespace flat2d::localization::registration
