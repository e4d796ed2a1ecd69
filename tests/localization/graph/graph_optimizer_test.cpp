// The batch optimizer on synthetic graphs with known truth: noise-free measurements are
// recovered exactly from perturbed starts by GN and LM; the posterior covariance matches the
// closed form of a one-edge graph and the dense inverse of H; gauge and failure handling.
#include "localization/graph/graph_optimizer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <ostream>
#include <random>

#include "localization/graph/graph_init.hpp"

namespace flat2d::localization::graph {

// Found by ADL in the enum's namespace: names the parameter in gtest/ctest listings.
void PrintTo(Solver solver, std::ostream* os) {
  *os << (solver == Solver::kGaussNewton ? "gauss_newton" : "levenberg_marquardt");
}

namespace {

// A square loop walked twice with loop closures between the laps: `truth` holds the poses.
struct Synthetic {
  PoseGraph graph;
  std::vector<Se2> truth;
};

Synthetic SquareLoops(unsigned seed, double noise) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Synthetic s;
  Se2 pose;
  const Eigen::Matrix3d info = Eigen::Vector3d(100.0, 100.0, 1000.0).asDiagonal();
  constexpr int kPerLap = 40;
  for (int k = 0; k < 2 * kPerLap; ++k) {
    s.truth.push_back(pose);
    s.graph.AddNode(Se2());
    const bool corner = k % 10 == 9;
    pose = pose * Se2(1.0, 0.0, corner ? std::numbers::pi / 2.0 : 0.0);
  }
  auto add_edge = [&](std::size_t i, std::size_t j) {
    const Se2 exact = s.truth[i].Inverse() * s.truth[j];
    // Braces: the draws are made in order (a call's arguments have none).
    const Se2 z = exact * Se2{noise * gauss(rng), noise * gauss(rng), 0.1 * noise * gauss(rng)};
    s.graph.betweens.push_back({i, j, z, info, AngleResidual::kWrapped});
  };
  for (std::size_t k = 1; k < s.truth.size(); ++k) add_edge(k - 1, k);
  for (std::size_t k = 0; k < kPerLap; k += 3) add_edge(k, k + kPerLap);
  return s;
}

void PerturbEstimates(PoseGraph& graph, unsigned seed, double sigma) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, sigma);
  for (std::size_t n = 1; n < graph.nodes.size(); ++n) {
    graph.nodes[n].estimate = Retract(graph.nodes[n].estimate,
                                      Eigen::Vector3d{gauss(rng), gauss(rng), 0.2 * gauss(rng)});
  }
}

class SolverTest : public ::testing::TestWithParam<Solver> {};

TEST_P(SolverTest, RecoversNoiseFreeTruthFromPerturbedStart) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    Synthetic s = SquareLoops(seed, 0.0);
    ASSERT_TRUE(InitializeFromOdometry(s.graph).ok());
    PerturbEstimates(s.graph, seed, 0.3);
    const OptimizationResult result = Optimize(s.graph, {.solver = GetParam()});
    EXPECT_TRUE(result.converged()) << "seed " << seed << " " << StopReasonName(result.stop_reason);
    EXPECT_LT(result.final_cost(), 1e-12) << "seed " << seed;
    for (std::size_t n = 0; n < s.truth.size(); ++n) {
      EXPECT_LT(ComponentDifference(s.graph.nodes[n].estimate, s.truth[n]).norm(), 1e-6)
          << "seed " << seed << " node " << n;
    }
    EXPECT_FALSE(s.graph.nodes[0].fixed) << "the gauge hold must not leak into the graph";
  }
}

INSTANTIATE_TEST_SUITE_P(GnAndLm, SolverTest,
                         ::testing::Values(Solver::kGaussNewton, Solver::kLevenbergMarquardt));

TEST(GraphOptimizerTest, LevenbergMarquardtNeverRaisesTheCost) {
  Synthetic s = SquareLoops(3, 0.05);
  ASSERT_TRUE(InitializeFromOdometry(s.graph).ok());
  PerturbEstimates(s.graph, 3, 0.5);
  const OptimizationResult result = Optimize(s.graph);
  ASSERT_GE(result.cost_history.size(), 2u);
  for (std::size_t k = 1; k < result.cost_history.size(); ++k) {
    EXPECT_LE(result.cost_history[k], result.cost_history[k - 1]);
  }
  EXPECT_TRUE(result.converged());
  EXPECT_LT(result.final_cost(), 0.01 * result.initial_cost());
}

TEST(GraphOptimizerTest, OneEdgeCovarianceIsTheMeasurementsInTheWorldFrame) {
  // Node 0 fixed facing +y; the edge's x axis is world y, so sigma_x shows up as world yy.
  PoseGraph graph;
  graph.AddNode(Se2(0.0, 0.0, std::numbers::pi / 2.0), /*fixed=*/true);
  graph.AddNode(Se2(0.3, 0.9, 1.4));
  const double sx = 0.2, sy = 0.05, st = 0.01;
  const Eigen::Matrix3d info = Eigen::Vector3d(1 / (sx * sx), 1 / (sy * sy), 1 / (st * st)).asDiagonal();
  graph.betweens.push_back({0, 1, Se2(1.0, 0.0, 0.0), info, AngleResidual::kWrapped});
  const OptimizationResult result = Optimize(graph);
  ASSERT_TRUE(result.converged());
  EXPECT_LT(ComponentDifference(graph.nodes[1].estimate, Se2(0.0, 1.0, std::numbers::pi / 2)).norm(), 1e-9);
  EXPECT_FALSE(MarginalCovariance(result.posterior, 0).ok());  // fixed
  const Result<Eigen::Matrix3d> cov = MarginalCovariance(result.posterior, 1);
  ASSERT_TRUE(cov.ok()) << cov.error().message;
  Eigen::Matrix3d expected = Eigen::Vector3d(sy * sy, sx * sx, st * st).asDiagonal();
  EXPECT_TRUE(cov->isApprox(expected, 1e-9)) << *cov;
}

TEST(GraphOptimizerTest, MarginalCovarianceEqualsDenseInverse) {
  Synthetic s = SquareLoops(11, 0.05);
  s.graph.priors.push_back({0, Se2(), Eigen::Matrix3d::Identity() * 1e4});  // gauge by prior
  ASSERT_TRUE(InitializeFromOdometry(s.graph).ok());
  const OptimizationResult result = Optimize(s.graph);
  ASSERT_TRUE(result.converged());
  ASSERT_EQ(result.posterior.block_of_node[0], 0);  // the prior leaves node 0 free
  const Eigen::MatrixXd dense = Eigen::MatrixXd(result.posterior.information).inverse();
  for (const std::size_t node : {0u, 17u, 79u}) {
    const Result<Eigen::Matrix3d> cov = MarginalCovariance(result.posterior, node);
    ASSERT_TRUE(cov.ok());
    const Eigen::Index b = 3 * result.posterior.block_of_node[node];
    EXPECT_TRUE(cov->isApprox(dense.block<3, 3>(b, b), 1e-8)) << "node " << node;
  }
  // Uncertainty grows away from the prior.
  EXPECT_LT(MarginalCovariance(result.posterior, 0)->trace(),
            MarginalCovariance(result.posterior, 25)->trace());
}

TEST(GraphOptimizerTest, UnconstrainedNodeFailsTheLinearSolve) {
  PoseGraph graph;
  graph.AddNode(Se2());
  graph.AddNode(Se2(1.0, 0.0, 0.0));
  graph.AddNode(Se2(2.0, 0.0, 0.0));  // no factor touches it
  graph.betweens.push_back({0, 1, Se2(1.0, 0.0, 0.0), Eigen::Matrix3d::Identity(), AngleResidual::kWrapped});
  const OptimizationResult gn = Optimize(graph, {.solver = Solver::kGaussNewton});
  EXPECT_EQ(gn.stop_reason, StopReason::kLinearSolveFailed);
}

TEST(GraphOptimizerTest, ChordalInitializationIsExactWithoutNoise) {
  Synthetic s = SquareLoops(5, 0.0);
  ASSERT_TRUE(InitializeChordal(s.graph).ok());
  for (std::size_t n = 0; n < s.truth.size(); ++n) {
    EXPECT_LT(ComponentDifference(s.graph.nodes[n].estimate, s.truth[n]).norm(), 1e-9) << n;
  }
}

TEST(GraphOptimizerTest, OdometryInitializationBridgesABrokenChain) {
  Synthetic s = SquareLoops(6, 0.0);
  s.graph.betweens.erase(s.graph.betweens.begin() + 20);  // the edge 20 -> 21
  ASSERT_TRUE(InitializeFromOdometry(s.graph).ok());
  for (std::size_t n = 0; n < s.truth.size(); ++n) {
    EXPECT_LT(ComponentDifference(s.graph.nodes[n].estimate, s.truth[n]).norm(), 1e-9) << n;
  }
  s.graph.nodes.push_back({999, Se2(), false, false});
  const Status isolated = InitializeFromOdometry(s.graph);
  ASSERT_FALSE(isolated.ok());
  EXPECT_EQ(isolated.error().message,
            "odometry initialization: vertex 999 is not connected to vertex 0");
}

}  // namespace
}  // namespace flat2d::localization::graph
