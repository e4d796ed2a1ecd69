#include "localization/mapping/odometry_scale.hpp"

#include <gtest/gtest.h>

#include <random>

namespace flat2d::localization::mapping {
namespace {

// A match 1 cm sure in both directions, and one of a corridor along x: 1 m sure along it.
const Eigen::Matrix3d kSure = Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal();
const Eigen::Matrix3d kCorridor = Eigen::Vector3d(1.0, 1e4, 1e6).asDiagonal();

TEST(OdometryScaleEstimate, IsTheRatioOfMatchedToOdometryDistanceAlongThePath) {
  OdometryScaleEstimate estimate(0.03, 0.05);
  std::mt19937 random(1);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int i = 0; i < 400; ++i) {
    const Se2 odometry(0.5, 0.02, 0.01);  // half a metre, a little sideways
    // Braces: the draws are made in order (a call's arguments have none).
    const Se2 matched{0.5 * 0.994 + noise(random), 0.02 * 0.994 + noise(random), 0.01};
    EXPECT_TRUE(estimate.Add(odometry, matched, kSure));
  }
  EXPECT_TRUE(estimate.ready());
  EXPECT_EQ(estimate.steps(), 400);
  EXPECT_NEAR(estimate.scale(), 0.994, 0.002);  // 1 cm per 0.5 m step over 400 steps: 0.001 sigma
}

TEST(OdometryScaleEstimate, IgnoresCorridorsAndTurnsOnTheSpot) {
  OdometryScaleEstimate estimate(0.03, 0.05);
  // A corridor's match returns the prediction: it would pull the scale to 1.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(estimate.Add(Se2(0.5, 0, 0), Se2(0.5, 0, 0), kCorridor));
  // Across the corridor the match is sure, but the step is sideways to nothing.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(estimate.Add(Se2(0.05, 0, 0.3), Se2(0.0, 0, 0.3), kSure));
  EXPECT_EQ(estimate.steps(), 0);
  EXPECT_FALSE(estimate.ready());
  EXPECT_EQ(estimate.scale(), 1.0);
  // A sideways step is judged along its own direction: y here, which the corridor pins.
  EXPECT_TRUE(estimate.Add(Se2(0, 0.5, 0), Se2(0, 0.49, 0), kCorridor));
}

TEST(OdometryScaleEstimate, IsReadyAfterTwentyStepsAndStaysWithinItsBounds) {
  OdometryScaleEstimate estimate(0.03, 0.05);
  for (int i = 0; i < 19; ++i) estimate.Add(Se2(1, 0, 0), Se2(1.2, 0, 0), kSure);
  EXPECT_FALSE(estimate.ready());
  estimate.Add(Se2(1, 0, 0), Se2(1.2, 0, 0), kSure);
  EXPECT_TRUE(estimate.ready());
  EXPECT_DOUBLE_EQ(estimate.scale(), 1.05);  // 1.2 measured, clamped to 1 + max_error
  estimate.Reset();
  EXPECT_EQ(estimate.steps(), 0);
  EXPECT_EQ(estimate.scale(), 1.0);
}

}  // namespace
}  // namespace flat2d::localization::mapping
