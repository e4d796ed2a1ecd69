// Factor math: analytic Jacobians against central differences over F1 perturbations, for
// random poses including headings near +-pi and both angle residuals; the chord residual
// reproduces SE-Sync's edge cost; max-mixture picks the likelier component.
#include "localization/graph/se2_factors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <ostream>
#include <random>

#include "localization/graph/graph_costs.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

// Found by ADL in the enum's namespace: names the parameter in gtest/ctest listings.
void PrintTo(AngleResidual angle, std::ostream* os) {
  *os << (angle == AngleResidual::kWrapped ? "wrapped" : "chord");
}

namespace {

constexpr double kPi = std::numbers::pi;

Se2 RandomPose(std::mt19937& rng, double extent) {
  std::uniform_real_distribution<double> position(-extent, extent);
  std::uniform_real_distribution<double> heading(-kPi, kPi);
  // Braces: the draws are made in order (a call's arguments have none).
  return Se2{position(rng), position(rng), heading(rng)};
}

// d error / d delta by central differences; the angle row is wrapped so a jump over +-pi
// of the perturbed error does not count as slope.
template <typename ErrorFn>
Eigen::Matrix3d NumericJacobian(const ErrorFn& error_of, const Se2& pose) {
  constexpr double kStep = 1e-6;
  Eigen::Matrix3d jacobian;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d delta = Eigen::Vector3d::Unit(k) * kStep;
    Eigen::Vector3d diff = error_of(Retract(pose, delta)) - error_of(Retract(pose, -delta));
    diff.z() = NormalizeAngle(diff.z());
    jacobian.col(k) = diff / (2.0 * kStep);
  }
  return jacobian;
}

class BetweenJacobianTest : public ::testing::TestWithParam<AngleResidual> {};

TEST_P(BetweenJacobianTest, MatchesCentralDifferences) {
  const AngleResidual angle = GetParam();
  const unsigned seed = 42;
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const Se2 pi = RandomPose(rng, 50.0);
    const Se2 pj = RandomPose(rng, 50.0);
    // Half the measurements near the truth (small errors), half arbitrary (large ones).
    const Se2 truth = pi.Inverse() * pj;
    const Se2 z = trial % 2 == 0 ? truth * Se2(0.1, -0.05, 0.02) : RandomPose(rng, 10.0);
    const BetweenLinearization lin = LinearizeBetween(pi, pj, z, angle);
    ASSERT_TRUE(lin.error.isApprox(BetweenError(pi, pj, z, angle), 1e-12)) << "seed " << seed;
    const Eigen::Matrix3d numeric_i =
        NumericJacobian([&](const Se2& p) { return BetweenError(p, pj, z, angle); }, pi);
    const Eigen::Matrix3d numeric_j =
        NumericJacobian([&](const Se2& p) { return BetweenError(pi, p, z, angle); }, pj);
    EXPECT_LT((lin.jacobian_i - numeric_i).cwiseAbs().maxCoeff(), 1e-5)
        << "seed " << seed << " trial " << trial << "\n" << lin.jacobian_i << "\nvs\n" << numeric_i;
    EXPECT_LT((lin.jacobian_j - numeric_j).cwiseAbs().maxCoeff(), 1e-5)
        << "seed " << seed << " trial " << trial << "\n" << lin.jacobian_j << "\nvs\n" << numeric_j;
  }
}

INSTANTIATE_TEST_SUITE_P(BothAngles, BetweenJacobianTest,
                         ::testing::Values(AngleResidual::kWrapped, AngleResidual::kChord));

TEST(BetweenErrorTest, ZeroAtTheTruthAndG2oFrame) {
  const Se2 pi(1.0, 2.0, 3.0);  // near pi, so the heading wraps
  const Se2 z(0.5, -0.2, 0.4);
  const Se2 pj = pi * z;
  EXPECT_LT(BetweenError(pi, pj, z).norm(), 1e-12);
  // A translation error d in j's frame shows up as d: e_t = Rz^T (Ri^T (tj - ti) - tz).
  const Se2 moved = pj * Se2(0.3, 0.1, 0.0);
  const Eigen::Vector3d e = BetweenError(pi, moved, z);
  EXPECT_NEAR(e.x(), 0.3, 1e-12);
  EXPECT_NEAR(e.y(), 0.1, 1e-12);
  EXPECT_NEAR(e.z(), 0.0, 1e-12);
}

TEST(BetweenErrorTest, ChordResidualGivesSeSyncEdgeCost) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    PoseGraph graph;
    graph.AddNode(RandomPose(rng, 20.0));
    graph.AddNode(RandomPose(rng, 20.0));
    Eigen::Matrix3d info;
    info << 40.0, 5.0, 0.0, 5.0, 300.0, 0.0, 0.0, 0.0, 900.0;
    graph.betweens.push_back({0, 1, RandomPose(rng, 5.0), info, AngleResidual::kWrapped});
    const PoseGraph sesync = ToSeSyncProblem(graph);
    const BetweenFactor& f = sesync.betweens.front();
    const Eigen::Vector3d e = BetweenError(graph.nodes[0].estimate, graph.nodes[1].estimate,
                                           f.measurement, f.angle);
    EXPECT_NEAR(e.dot(f.information * e), SeSyncCost(graph), 1e-9 * SeSyncCost(graph));
  }
}

TEST(PriorErrorTest, ComponentDifferenceWithIdentityJacobian) {
  const Se2 z(1.0, -1.0, kPi - 0.1);
  const Se2 x(1.5, -0.5, -kPi + 0.1);  // 0.2 rad past the wrap
  const Eigen::Vector3d e = PriorError(x, z);
  EXPECT_NEAR(e.x(), 0.5, 1e-12);
  EXPECT_NEAR(e.y(), 0.5, 1e-12);
  EXPECT_NEAR(e.z(), 0.2, 1e-12);
  const Eigen::Matrix3d numeric = NumericJacobian([&](const Se2& p) { return PriorError(p, z); }, x);
  EXPECT_TRUE(numeric.isApprox(Eigen::Matrix3d::Identity(), 1e-6)) << numeric;
}

TEST(MaxMixtureTest, SmallErrorsPickTheMatchLargeErrorsTheNullHypothesis) {
  const Eigen::Matrix3d match = Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal();  // 10 cm, 2.9 deg
  const MaxMixture mixture = MakeNullHypothesisMixture(match, 1e-3, 1e-6);
  const MixtureChoice small = SelectMixtureComponent(mixture, Eigen::Vector3d(0.05, 0.0, 0.01));
  EXPECT_EQ(small.component, 0u);
  EXPECT_DOUBLE_EQ(small.offset, 0.0);
  EXPECT_TRUE(small.information.isApprox(match));
  const MixtureChoice large = SelectMixtureComponent(mixture, Eigen::Vector3d(5.0, -3.0, 1.0));
  EXPECT_EQ(large.component, 1u);
  EXPECT_TRUE(large.information.isApprox(match * 1e-6));
  // The null's offset is 2 log(w_match |L|^1/2 / (w_null |L_null|^1/2)) = 2 log(999) + 3 log(1e6).
  EXPECT_NEAR(large.offset, 2.0 * std::log(0.999 / 1e-3) + 3.0 * std::log(1e6), 1e-9);
  // The chosen cost is the minimum over components: never above either one's cost.
  for (double r = 0.0; r < 3.0; r += 0.01) {
    const Eigen::Vector3d e(r, r, 0.1 * r);
    const MixtureChoice c = SelectMixtureComponent(mixture, e);
    EXPECT_LE(c.cost, e.dot(match * e) + 1e-12);
    EXPECT_LE(c.cost, e.dot(1e-6 * match * e) + large.offset + 1e-9);
  }
}

TEST(MaxMixtureTest, SwitchesWhereTheLikelihoodsCross) {
  // One dimension in effect: e = (r, 0, 0) with information a (match) and a s (null):
  // a r^2 = a s r^2 + offset  =>  r^2 = offset / (a (1 - s)).
  const double a = 100.0;
  const double s = 1e-4;
  const MaxMixture mixture =
      MakeNullHypothesisMixture(Eigen::Vector3d(a, a, a).asDiagonal(), 0.01, s);
  const double offset = 2.0 * std::log(0.99 / 0.01) - 3.0 * std::log(s);
  const double r_switch = std::sqrt(offset / (a * (1.0 - s)));
  EXPECT_EQ(SelectMixtureComponent(mixture, Eigen::Vector3d(0.99 * r_switch, 0, 0)).component, 0u);
  EXPECT_EQ(SelectMixtureComponent(mixture, Eigen::Vector3d(1.01 * r_switch, 0, 0)).component, 1u);
}

}  // namespace
}  // namespace flat2d::localization::graph
