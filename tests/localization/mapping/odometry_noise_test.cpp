#include "localization/mapping/odometry_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flat2d::localization::mapping {
namespace {

// 2000 steps of 1 m straight ahead.
std::vector<Se2> Straight() {
  std::vector<Se2> poses;
  for (int i = 0; i <= 2000; ++i) poses.emplace_back(static_cast<double>(i), 0.0, 0.0);
  return poses;
}

TEST(OdometryNoise, IsReproducibleForASeedAndDiffersAcrossSeeds) {
  OdometryNoiseModel model;
  const auto a = CorruptOdometry(Straight(), model);
  const auto b = CorruptOdometry(Straight(), model);
  model.seed = 2;
  const auto c = CorruptOdometry(Straight(), model);
  ASSERT_EQ(a.size(), 2001u);
  EXPECT_EQ(a.back().x(), b.back().x());
  EXPECT_EQ(a.back().theta(), b.back().theta());
  EXPECT_NE(a.back().x(), c.back().x());
  EXPECT_EQ(a.front().x(), 0.0);  // starts at the reference
}

TEST(OdometryNoise, ZeroModelReproducesTheReference) {
  const OdometryNoiseModel zero{0.0, 0.0, 0.0, 0.0, 0.0, 5};
  const auto reference = Straight();
  const auto noisy = CorruptOdometry(reference, zero);
  EXPECT_NEAR((noisy.back().translation() - reference.back().translation()).norm(), 0.0, 1e-9);
}

TEST(OdometryNoise, StepErrorsHaveTheModelledSpread) {
  OdometryNoiseModel model;
  model.scale_sigma = 0.0;
  const auto noisy = CorruptOdometry(Straight(), model);
  double forward = 0.0, forward_sq = 0.0, heading_sq = 0.0;
  const auto n = static_cast<double>(noisy.size() - 1);
  for (std::size_t i = 1; i < noisy.size(); ++i) {
    const Se2 step = noisy[i - 1].Inverse() * noisy[i];
    forward += step.x() - 1.0;
    forward_sq += (step.x() - 1.0) * (step.x() - 1.0);
    heading_sq += step.theta() * step.theta();
  }
  // 2000 samples: the standard deviation is within about 5 % (3 sigma) of the model's.
  EXPECT_NEAR(forward / n, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(forward_sq / n), model.translation_fraction, 0.1 * model.translation_fraction);
  EXPECT_NEAR(std::sqrt(heading_sq / n), model.rotation_per_metre, 0.1 * model.rotation_per_metre);
}

TEST(OdometryNoise, InformationFollowsTheModelWithFloors) {
  const OdometryNoiseModel model;
  const Eigen::Matrix3d moving = OdometryInformation(Se2(1.0, 0.0, 0.0), model);
  EXPECT_NEAR(moving(0, 0), 1.0 / std::pow(0.06, 2), 1e-6);
  EXPECT_NEAR(moving(2, 2), 1.0 / std::pow(0.01, 2), 1e-6);
  const Eigen::Matrix3d still = OdometryInformation(Se2(), model);
  EXPECT_TRUE(still.allFinite());
  EXPECT_GT(still(0, 0), moving(0, 0));
}

}  // namespace
}  // namespace flat2d::localization::mapping
