#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "localization/landmarks/landmark_factors.hpp"
#include "tests/localization/landmarks/random_geometry.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::CentralDifference;
using testing::JacobiansAgree;
using testing::RandomOrthogonal;
using testing::RandomPose;
using testing::RandomUnit;
using testing::RandomVector;
using testing::TranslationScale;

constexpr int kLineFactorCases = 100;

// Generic, through-the-origin and far world lines.
PluckerLine WorldLine(std::mt19937& rng, int i) {
  const Eigen::Vector3d direction = RandomUnit(rng);
  const Eigen::Vector3d point = i % 3 == 1 ? 2.0 * direction : RandomVector(rng, i % 3 == 2 ? 200.0 : 10.0);
  return *LineFromPointDirection(point, direction);
}

// The world line seen from the sensor, through two of its points: independent of Transformed().
PluckerLine SeenFrom(const Eigen::Isometry3d& world_T_sensor, const PluckerLine& world) {
  const Eigen::Isometry3d sensor_T_world = world_T_sensor.inverse();
  const Eigen::Vector3d p0 = sensor_T_world * ClosestPointToOrigin(world);
  const Eigen::Vector3d p1 = sensor_T_world * (ClosestPointToOrigin(world) + 5.0 * Direction(world));
  return *LineFromPointDirection(p0, p1 - p0);
}

Eigen::Vector4d LineErrorAt(const Eigen::Isometry3d& pose, const OrthonormalLine& line, const PluckerLine& measured) {
  const std::optional<Eigen::Vector4d> error = LineError(pose, line, measured);
  EXPECT_TRUE(error.has_value());
  return error.value_or(Eigen::Vector4d::Constant(1e9));
}

TEST(LineFactor, ZeroAtTruthWhicheverWayTheLinesPoint) {
  const unsigned seed = 1315;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kLineFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const PluckerLine world = WorldLine(rng, i);
    const PluckerLine measured = SeenFrom(world_T_sensor, world);
    const double tolerance = 1e-9 * TranslationScale(i);
    EXPECT_LE(LineErrorAt(world_T_sensor, ToOrthonormal(world), measured).norm(), tolerance) << "case " << i;
    const PluckerLine flipped{-measured.a, -measured.b};
    EXPECT_LE(LineErrorAt(world_T_sensor, ToOrthonormal(world), flipped).norm(), tolerance) << "case " << i;
  }
}

TEST(LineFactor, ErrorMeasuresKnownMotionsOfTheSensor) {
  const unsigned seed = 1316;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> amount(-0.5, 0.5);
  for (int i = 0; i < kLineFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const PluckerLine world = WorldLine(rng, i);
    const OrthonormalLine landmark = ToOrthonormal(world);
    const PluckerLine measured = SeenFrom(world_T_sensor, world);
    const double tolerance = 1e-9 * TranslationScale(i);
    // Stepping the sensor by o across the line offsets the line by |o|, direction unchanged.
    const Eigen::Vector3d across = amount(rng) * RandomOrthogonal(rng, Direction(measured));
    Eigen::Isometry3d moved = world_T_sensor;
    moved.translation() += world_T_sensor.linear() * across;
    const Eigen::Vector4d shifted = LineErrorAt(moved, landmark, measured);
    EXPECT_LE(shifted.head<2>().norm(), tolerance) << "case " << i;
    EXPECT_NEAR(shifted.tail<2>().norm(), across.norm(), tolerance) << "case " << i;
    // Stepping along the line changes nothing.
    moved.translation() = world_T_sensor.translation() + 3.0 * (world_T_sensor.linear() * Direction(measured));
    EXPECT_LE(LineErrorAt(moved, landmark, measured).norm(), tolerance) << "case " << i;
    // Turning by beta about an axis across the line turns its direction by beta.
    const double beta = amount(rng);
    const Eigen::Isometry3d turned = world_T_sensor * testing::Rotation(RandomOrthogonal(rng, Direction(measured)), beta);
    EXPECT_NEAR(LineErrorAt(turned, landmark, measured).head<2>().norm(), std::abs(std::sin(beta)), 1e-9) << "case " << i;
  }
}

TEST(LineFactor, ErrorGrowsWithThePerturbation) {
  const unsigned seed = 1317;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kLineFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const PluckerLine world = WorldLine(rng, i);
    const OrthonormalLine landmark = ToOrthonormal(world);
    const PluckerLine measured = SeenFrom(world_T_sensor, world);
    const Vector6d pose_step = (Vector6d() << RandomVector(rng, 1.0), RandomVector(rng, 1.0)).finished();
    const Eigen::Vector4d line_step(RandomVector(rng, 1.0).homogeneous());
    double pose_previous = 0.0;
    double line_previous = 0.0;
    // Small steps: theta moves a line at distance d by (1 + d^2) theta, 4e4 theta at 200 m.
    for (const double size : {1e-7, 1e-6, 1e-5, 1e-4}) {
      const double pose_error = LineErrorAt(RetractPose(world_T_sensor, size * pose_step), landmark, measured).norm();
      const double line_error = LineErrorAt(world_T_sensor, Retract(landmark, size * line_step), measured).norm();
      EXPECT_GT(pose_error, pose_previous) << "case " << i << " step " << size;
      EXPECT_GT(line_error, line_previous) << "case " << i << " step " << size;
      pose_previous = pose_error;
      line_previous = line_error;
    }
  }
}

TEST(LineFactor, AnalyticJacobiansEqualCentralDifferences) {
  const unsigned seed = 1318;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kLineFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const PluckerLine world = WorldLine(rng, i);
    // The landmark a little off the measured line, so that the error's own terms are
    // non-zero too. (Moved in space, not by theta: near alpha = pi / 2 a step in theta sends
    // a line to infinity, where tan has no useful central difference.)
    const OrthonormalLine landmark = ToOrthonormal(*LineFromPointDirection(
        ClosestPointToOrigin(world) + RandomVector(rng, 0.3), Direction(world) + RandomVector(rng, 0.1)));
    const PluckerLine measured = SeenFrom(world_T_sensor, world);
    const std::optional<LineFactorLinearization> linear = LinearizeLine(world_T_sensor, landmark, measured);
    ASSERT_TRUE(linear.has_value());
    EXPECT_LE((linear->error - LineErrorAt(world_T_sensor, landmark, measured)).norm(), 1e-12);
    const auto by_pose = [&](const Vector6d& step) {
      return LineErrorAt(RetractPose(world_T_sensor, step), landmark, measured);
    };
    const auto by_line = [&](const Eigen::Vector4d& step) {
      return LineErrorAt(world_T_sensor, Retract(landmark, step), measured);
    };
    const Eigen::Matrix<double, 4, 6> numeric_pose = CentralDifference<4, 6>(by_pose, 1e-6);
    const Eigen::Matrix4d numeric_line = CentralDifference<4, 4>(by_line, 1e-6);
    EXPECT_TRUE(JacobiansAgree(linear->jacobian_pose, numeric_pose, 1e-6))
        << "case " << i << "\nanalytic\n" << linear->jacobian_pose << "\nnumeric\n" << numeric_pose;
    EXPECT_TRUE(JacobiansAgree(linear->jacobian_line, numeric_line, 1e-6))
        << "case " << i << "\nanalytic\n" << linear->jacobian_line << "\nnumeric\n" << numeric_line;
  }
}

// The orthonormal chart is singular for a line through the origin of its frame (theta_1
// turns the line about itself and an offset along u3 is second order), like polar
// coordinates at their centre. Anchoring the landmark's frame off the line, here at the
// sensor, restores four independent directions and leaves the error unchanged.
TEST(LineFactor, LandmarkAnchoredOffTheLineHasAFullRankChart) {
  const unsigned seed = 1319;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kLineFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, 10.0);
    const PluckerLine world = *LineFromPointDirection(Eigen::Vector3d::Zero(), RandomUnit(rng));
    const PluckerLine measured = SeenFrom(world_T_sensor, world);
    const std::optional<LineFactorLinearization> at_origin =
        LinearizeLine(world_T_sensor, ToOrthonormal(world), measured);
    ASSERT_TRUE(at_origin.has_value());
    const Eigen::JacobiSVD<Eigen::Matrix4d> singular(at_origin->jacobian_line);
    EXPECT_LT(singular.singularValues()(3), 1e-9 * singular.singularValues()(0)) << "case " << i;

    Eigen::Isometry3d anchor_T_world = Eigen::Isometry3d::Identity();
    anchor_T_world.translation() = -world_T_sensor.translation();
    const Eigen::Isometry3d anchor_T_sensor = anchor_T_world * world_T_sensor;
    const OrthonormalLine anchored = ToOrthonormal(Transformed(anchor_T_world, world));
    const std::optional<LineFactorLinearization> linear = LinearizeLine(anchor_T_sensor, anchored, measured);
    ASSERT_TRUE(linear.has_value());
    const Eigen::JacobiSVD<Eigen::Matrix4d> regular(linear->jacobian_line);
    EXPECT_GT(regular.singularValues()(3), 1e-3 * regular.singularValues()(0)) << "case " << i;
    EXPECT_LE((linear->jacobian_pose - at_origin->jacobian_pose).norm(), 1e-9 * at_origin->jacobian_pose.norm());
    const Eigen::Vector4d step(0.05 * RandomVector(rng, 1.0).homogeneous());
    // The same moved line gives the same error whichever frame holds it.
    const OrthonormalLine moved = Retract(anchored, step);
    const PluckerLine moved_in_world = Transformed(anchor_T_world.inverse(), *ToPlucker(moved));
    const Eigen::Vector4d error = LineErrorAt(anchor_T_sensor, moved, measured);
    EXPECT_LE((error - LineErrorAt(world_T_sensor, ToOrthonormal(moved_in_world), measured)).norm(), 1e-9);
    EXPECT_LE(LineErrorAt(anchor_T_sensor, anchored, measured).norm(), 1e-9) << "case " << i;
  }
}

TEST(LineFactor, LandmarkAtInfinityIsReported) {
  OrthonormalLine at_infinity;
  at_infinity.W = Eigen::Rotation2Dd(1.5707963267948966).toRotationMatrix();
  const PluckerLine measured = *LineFromPointDirection(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(LineError(Eigen::Isometry3d::Identity(), at_infinity, measured).has_value());
  EXPECT_FALSE(LinearizeLine(Eigen::Isometry3d::Identity(), at_infinity, measured).has_value());
}

}  // namespace
}  // namespace flat2d::localization::landmarks
