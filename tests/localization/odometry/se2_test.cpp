#include "localization/odometry/se2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace flat2d::localization {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr unsigned kSeed = 42;

Se2 RandomPose(std::mt19937& rng, double extent = 100.0) {
  std::uniform_real_distribution<double> position(-extent, extent);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  // Braces: the draws are made in order (a call's arguments have none).
  return Se2{position(rng), position(rng), angle(rng)};
}

// Numeric Jacobian of f: (x, y, theta) -> (x, y, theta), central differences, angles wrapped.
template <typename F>
Eigen::Matrix3d NumericJacobian(F f, const Se2& at) {
  constexpr double kStep = 1e-6;
  Eigen::Matrix3d j;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d plus = at.Vector();
    Eigen::Vector3d minus = at.Vector();
    plus(i) += kStep;
    minus(i) -= kStep;
    const Se2 f_plus = f(Se2(plus.x(), plus.y(), plus.z()));
    const Se2 f_minus = f(Se2(minus.x(), minus.y(), minus.z()));
    j.col(i) = ComponentDifference(f_plus, f_minus) / (2.0 * kStep);
  }
  return j;
}

TEST(NormalizeAngle, WrapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(NormalizeAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(NormalizeAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(NormalizeAngle(-kPi), kPi);
  EXPECT_NEAR(NormalizeAngle(3.0 * kPi), kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(2.0 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-2.0 * kPi - 0.25), -0.25, 1e-12);
  EXPECT_NEAR(NormalizeAngle(1000.0), 1000.0 - 159.0 * 2.0 * kPi, 1e-9);
}

TEST(Se2, ComposeAndInverseAgainstMatrices) {
  std::mt19937 rng(kSeed);
  std::printf("seed %u\n", kSeed);
  for (int i = 0; i < 50; ++i) {
    const Se2 a = RandomPose(rng);
    const Se2 b = RandomPose(rng);
    Eigen::Matrix3d ma = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d mb = Eigen::Matrix3d::Identity();
    ma.topLeftCorner<2, 2>() = a.Rotation();
    ma.topRightCorner<2, 1>() = a.translation();
    mb.topLeftCorner<2, 2>() = b.Rotation();
    mb.topRightCorner<2, 1>() = b.translation();
    const Eigen::Matrix3d mc = ma * mb;
    const Se2 c = a * b;
    EXPECT_NEAR(c.x(), mc(0, 2), 1e-9);
    EXPECT_NEAR(c.y(), mc(1, 2), 1e-9);
    EXPECT_NEAR(c.theta(), std::atan2(mc(1, 0), mc(0, 0)), 1e-12);
    const Se2 identity = a * a.Inverse();
    EXPECT_NEAR(identity.translation().norm(), 0.0, 1e-12);
    EXPECT_NEAR(identity.theta(), 0.0, 1e-12);
    const Eigen::Vector2d p(3.0, -4.0);
    EXPECT_NEAR((a.Inverse() * (a * p) - p).norm(), 0.0, 1e-12);
  }
}

TEST(Se2, ExpLogRoundTripIncludingSmallAndNearPiAngles) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> rho(-20.0, 20.0);
  for (double phi : {0.0, 1e-12, -3e-9, 1e-5, 9.99e-3, 1.01e-2, 0.5, -2.0, 3.1, kPi - 1e-9, kPi}) {
    const Eigen::Vector3d xi{rho(rng), rho(rng), phi};
    const Eigen::Vector3d back = Se2::Exp(xi).Log();
    EXPECT_NEAR((back - xi).norm(), 0.0, 1e-9 * (1.0 + xi.norm())) << "phi " << phi;
  }
  for (int i = 0; i < 50; ++i) {
    const Se2 pose = RandomPose(rng);
    const Se2 back = Se2::Exp(pose.Log());
    EXPECT_NEAR(ComponentDifference(back, pose).norm(), 0.0, 1e-9);
  }
}

TEST(Se2, ExpIsTheArcAUnicycleDrives) {
  // Radius 10 m, a quarter turn: from the origin to (10, 10) facing +y.
  const Se2 quarter = Arc(10.0 * kPi / 2.0, kPi / 2.0);
  EXPECT_NEAR(quarter.x(), 10.0, 1e-12);
  EXPECT_NEAR(quarter.y(), 10.0, 1e-12);
  EXPECT_NEAR(quarter.theta(), kPi / 2.0, 1e-15);
  const Se2 straight = Arc(5.0, 0.0);
  EXPECT_EQ(straight.x(), 5.0);
  EXPECT_EQ(straight.y(), 0.0);
  // Series and closed form agree at the switch (|phi| = 1e-2); the reference keeps its
  // digits with 1 - cos = 2 sin^2(phi / 2).
  for (double phi : {0.99999e-2, 1.00001e-2}) {
    const Se2 arc = Arc(1.0, phi);
    EXPECT_NEAR(arc.x(), std::sin(phi) / phi, 1e-15);
    EXPECT_NEAR(arc.y(), 2.0 * std::sin(0.5 * phi) * std::sin(0.5 * phi) / phi, 1e-17);
  }
}

TEST(Se2, InterpolationFollowsTheGeodesic) {
  const Se2 a(1.0, 2.0, 0.3);
  const Se2 b = a * Arc(4.0, 1.2);
  const Se2 half = Interpolate(a, b, 0.5);
  const Se2 expected = a * Arc(2.0, 0.6);
  EXPECT_NEAR(ComponentDifference(half, expected).norm(), 0.0, 1e-12);
  EXPECT_NEAR(ComponentDifference(Interpolate(a, b, 0.0), a).norm(), 0.0, 1e-12);
  EXPECT_NEAR(ComponentDifference(Interpolate(a, b, 1.0), b).norm(), 0.0, 1e-12);
}

TEST(Se2, ComposeJacobiansMatchNumericDifferences) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < 50; ++i) {
    const Se2 a = RandomPose(rng);
    const Se2 b = RandomPose(rng, 5.0);
    const ComposeJacobians j = ComposeJacobian(a, b);
    const Eigen::Matrix3d numeric_a = NumericJacobian([&](const Se2& x) { return x * b; }, a);
    const Eigen::Matrix3d numeric_b = NumericJacobian([&](const Se2& x) { return a * x; }, b);
    EXPECT_LT((j.wrt_a - numeric_a).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_LT((j.wrt_b - numeric_b).cwiseAbs().maxCoeff(), 1e-6);
    const Eigen::Matrix3d numeric_inverse =
        NumericJacobian([](const Se2& x) { return x.Inverse(); }, a);
    EXPECT_LT((InverseJacobian(a) - numeric_inverse).cwiseAbs().maxCoeff(), 1e-6);
  }
}

TEST(Se2, ArcJacobianMatchesNumericDifferences) {
  constexpr double kStep = 1e-6;
  for (double distance : {0.0, 0.1, 3.0, -2.0}) {
    for (double phi : {0.0, 1e-4, 5e-3, 0.02, 0.7, -1.5}) {
      const Eigen::Matrix<double, 3, 2> j = ArcJacobian(distance, phi);
      const Eigen::Vector3d d_distance =
          ComponentDifference(Arc(distance + kStep, phi), Arc(distance - kStep, phi)) / (2 * kStep);
      const Eigen::Vector3d d_phi =
          ComponentDifference(Arc(distance, phi + kStep), Arc(distance, phi - kStep)) / (2 * kStep);
      EXPECT_LT((j.col(0) - d_distance).cwiseAbs().maxCoeff(), 1e-8) << distance << " " << phi;
      EXPECT_LT((j.col(1) - d_phi).cwiseAbs().maxCoeff(), 1e-8) << distance << " " << phi;
    }
  }
}

}  // namespace
}  // namespace flat2d::localization
