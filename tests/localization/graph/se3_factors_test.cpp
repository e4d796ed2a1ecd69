// SE(3) factor math: analytic Jacobians (G3) against central differences over G1
// perturbations, for random poses with small and large errors (up to 170 degrees); the
// error is g2o's; the same error with ToSeSyncProblem's weights is SE-Sync's edge cost; the
// retraction stays on SO(3).
#include "localization/graph/se3_factors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "localization/graph/se3_costs.hpp"
#include "tests/localization/graph/se3_synthetic.hpp"

namespace flat2d::localization::graph {
namespace {

using synthetic::RandomPose;

constexpr double kPi = std::numbers::pi;

template <typename ErrorFn>
Matrix6d NumericJacobian(const ErrorFn& error_of, const Eigen::Isometry3d& pose) {
  constexpr double kStep = 1e-6;
  Matrix6d jacobian;
  for (int k = 0; k < 6; ++k) {
    const Vector6d delta = Vector6d::Unit(k) * kStep;
    jacobian.col(k) = (error_of(Retract(pose, delta)) - error_of(Retract(pose, -delta))) / (2.0 * kStep);
  }
  return jacobian;
}

TEST(Se3BetweenTest, JacobiansMatchCentralDifferences) {
  const unsigned seed = 42;
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Isometry3d xi = RandomPose(rng, 50.0, kPi);
    const Eigen::Isometry3d xj = RandomPose(rng, 50.0, kPi);
    // A third near the truth (small errors), the rest up to 170 degrees off: q.w stays away
    // from 0, where g2o's w >= 0 convention flips the error's sign.
    const Eigen::Isometry3d truth = xi.inverse() * xj;
    const double max_angle = trial % 3 == 0 ? 0.05 : 170.0 * kPi / 180.0;
    const Eigen::Isometry3d z = truth * RandomPose(rng, trial % 3 == 0 ? 0.1 : 5.0, max_angle);
    const Se3BetweenLinearization lin = LinearizeSe3Between(xi, xj, z);
    ASSERT_TRUE(lin.error.isApprox(Se3BetweenError(xi, xj, z), 1e-12)) << "seed " << seed;
    const Matrix6d numeric_i =
        NumericJacobian([&](const Eigen::Isometry3d& p) { return Se3BetweenError(p, xj, z); }, xi);
    const Matrix6d numeric_j =
        NumericJacobian([&](const Eigen::Isometry3d& p) { return Se3BetweenError(xi, p, z); }, xj);
    EXPECT_LT((lin.jacobian_i - numeric_i).cwiseAbs().maxCoeff(), 1e-5)
        << "seed " << seed << " trial " << trial << "\n" << lin.jacobian_i << "\nvs\n" << numeric_i;
    EXPECT_LT((lin.jacobian_j - numeric_j).cwiseAbs().maxCoeff(), 1e-5)
        << "seed " << seed << " trial " << trial << "\n" << lin.jacobian_j << "\nvs\n" << numeric_j;
  }
}

TEST(Se3BetweenTest, ZeroAtTheTruthAndG2oConvention) {
  std::mt19937 rng(3);
  const Eigen::Isometry3d xi = RandomPose(rng, 10.0, kPi);
  const Eigen::Isometry3d z = RandomPose(rng, 2.0, 1.0);
  const Eigen::Isometry3d xj = xi * z;
  EXPECT_LT(Se3BetweenError(xi, xj, z).norm(), 1e-12);
  // Moving j by d in its own frame and turning it by 0.2 rad about its z axis: e = (d,
  // sin(0.1) z) - g2o's quaternion vector part, no factor 2.
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.translation() = Eigen::Vector3d(0.3, -0.1, 0.2);
  offset.linear() = ExpSo3(Eigen::Vector3d(0.0, 0.0, 0.2));
  const Vector6d e = Se3BetweenError(xi, xj * offset, z);
  Vector6d expected;
  expected << 0.3, -0.1, 0.2, 0.0, 0.0, std::sin(0.1);
  EXPECT_TRUE(e.isApprox(expected, 1e-12)) << e.transpose();
  // The other way round the quaternion's w stays positive and the sign follows the turn.
  const Vector6d back = Se3BetweenError(xi, xj * offset.inverse(), z);
  EXPECT_NEAR(back[5], -std::sin(0.1), 1e-12);
}

TEST(Se3BetweenTest, SeSyncWeightsMakeTheErrorSeSyncsEdgeCost) {
  const unsigned seed = 11;
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 100; ++trial) {
    Se3PoseGraph graph;
    graph.AddNode(RandomPose(rng, 20.0, kPi));
    graph.AddNode(RandomPose(rng, 20.0, kPi));
    graph.betweens.push_back({0, 1, RandomPose(rng, 5.0, kPi), synthetic::TestInformation()});
    const double f = SeSyncCost(graph);
    EXPECT_NEAR(G2oChi2(ToSeSyncProblem(graph)), f, 1e-9 * f) << "seed " << seed << " trial " << trial;
  }
  // The weights of REFERENCE_RESULTS.md 1a: tau = 3 / tr(L_tt^-1), kappa = 3 / (2 tr(L_RR^-1)).
  Matrix6d isotropic = Matrix6d::Zero();
  isotropic.diagonal() << 10.0, 10.0, 10.0, 400.0, 400.0, 400.0;
  EXPECT_NEAR(SeSyncWeightsOf(isotropic).tau, 10.0, 1e-12);
  EXPECT_NEAR(SeSyncWeightsOf(isotropic).kappa, 200.0, 1e-12);
}

TEST(Se3RetractTest, StaysOnSo3AndComposesOnTheRight) {
  std::mt19937 rng(5);
  Eigen::Isometry3d pose = RandomPose(rng, 5.0, kPi);
  Vector6d delta;
  delta << 0.5, -0.2, 0.1, 0.3, -0.4, 0.2;
  const Eigen::Isometry3d moved = Retract(pose, delta);
  EXPECT_TRUE(moved.translation().isApprox(pose.translation() + delta.head<3>(), 1e-12));
  EXPECT_TRUE(moved.linear().isApprox(pose.linear() * ExpSo3(delta.tail<3>()), 1e-12));
  EXPECT_TRUE(Retract(pose, Vector6d::Zero()).isApprox(pose, 1e-12));
  for (int k = 0; k < 10000; ++k) pose = Retract(pose, 0.01 * delta);
  EXPECT_LT((pose.linear().transpose() * pose.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(pose.linear().determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace flat2d::localization::graph
