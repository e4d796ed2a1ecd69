// The SE(3) batch optimizer and initializations on synthetic corkscrew graphs with known
// truth: noise-free measurements are recovered from perturbed starts by GN and LM under both
// objectives (g2o chi2, SE-Sync f), also with reversed edges far from the origin; LM never
// raises the cost; chordal and odometry starts are exact without noise; FIX holds the gauge.
#include "localization/graph/se3_graph_optimizer.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <ostream>
#include <random>

#include "localization/graph/se3_costs.hpp"
#include "localization/graph/se3_init.hpp"
#include "tests/localization/graph/se3_synthetic.hpp"
#include "tests/testing/pose_error.hpp"

namespace flat2d::localization::graph {

// Found by ADL: names the parameters in gtest/ctest listings.
void PrintTo(Solver solver, std::ostream* os) {
  *os << (solver == Solver::kGaussNewton ? "gauss_newton" : "levenberg_marquardt");
}

namespace {

using synthetic::Corkscrew;
using synthetic::Se3Synthetic;

// Moves every node but the first by a random G1 increment (sigma metres and radians).
void Perturb(Se3PoseGraph& graph, unsigned seed, double sigma) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, sigma);
  for (std::size_t n = 1; n < graph.nodes.size(); ++n) {
    Vector6d delta;
    for (int c = 0; c < 6; ++c) delta[c] = gauss(rng);
    graph.nodes[n].estimate = Retract(graph.nodes[n].estimate, delta);
  }
}

// The largest distance and angle between the estimates and the truth.
flat2d::testing::PoseError WorstError(const Se3PoseGraph& graph,
                                      const std::vector<Eigen::Isometry3d>& truth) {
  flat2d::testing::PoseError worst{0.0, 0.0};
  for (std::size_t n = 0; n < truth.size(); ++n) {
    const flat2d::testing::PoseError e = flat2d::testing::PoseErrorOf(graph.nodes[n].estimate, truth[n]);
    worst.translation_m = std::max(worst.translation_m, e.translation_m);
    worst.rotation_deg = std::max(worst.rotation_deg, e.rotation_deg);
  }
  return worst;
}

// Every node and measurement moved into a frame far away (1 km, 2.5 rad), and every other
// edge reversed (j -> i with the inverse measurement).
void FarAndReversed(Se3Synthetic& s) {
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(1000.0, -700.0, 50.0);
  far.linear() = ExpSo3(Eigen::Vector3d(1.5, -1.0, 1.7));
  for (std::size_t n = 0; n < s.truth.size(); ++n) {
    s.truth[n] = far * s.truth[n];
    s.graph.nodes[n].estimate = s.truth[n];
  }
  for (std::size_t e = 0; e < s.graph.betweens.size(); e += 2) {
    Se3BetweenFactor& f = s.graph.betweens[e];
    std::swap(f.from, f.to);
    f.measurement = f.measurement.inverse();
  }
}

struct SolverCase {
  Solver solver;
  bool sesync;
};

void PrintTo(const SolverCase& c, std::ostream* os) {
  PrintTo(c.solver, os);
  *os << (c.sesync ? "/sesync" : "/g2o");
}

class Se3SolverTest : public ::testing::TestWithParam<SolverCase> {};

TEST_P(Se3SolverTest, RecoversNoiseFreeTruthFromPerturbedStarts) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    Se3Synthetic s = Corkscrew(seed, 30, 0.0);
    if (seed % 2 == 0) FarAndReversed(s);
    Perturb(s.graph, seed, 0.2);
    Se3PoseGraph problem = GetParam().sesync ? ToSeSyncProblem(s.graph) : s.graph;
    const OptimizationResult result = Optimize(problem, {.solver = GetParam().solver});
    const flat2d::testing::PoseError worst = WorstError(problem, s.truth);
    std::printf("seed %u: %d iterations, cost %.3g -> %.3g, worst %.2g m %.2g deg\n", seed,
                result.iterations, result.initial_cost(), result.final_cost(), worst.translation_m,
                worst.rotation_deg);
    EXPECT_TRUE(result.converged()) << "seed " << seed << " " << StopReasonName(result.stop_reason);
    EXPECT_LT(result.final_cost(), 1e-12 * result.initial_cost()) << "seed " << seed;
    EXPECT_LT(worst.translation_m, 1e-6) << "seed " << seed;
    EXPECT_LT(worst.rotation_deg, 1e-6) << "seed " << seed;
    EXPECT_FALSE(problem.nodes[0].fixed) << "the gauge hold must not leak into the graph";
  }
}

INSTANTIATE_TEST_SUITE_P(GnAndLm, Se3SolverTest,
                         ::testing::Values(SolverCase{Solver::kGaussNewton, false},
                                           SolverCase{Solver::kGaussNewton, true},
                                           SolverCase{Solver::kLevenbergMarquardt, false},
                                           SolverCase{Solver::kLevenbergMarquardt, true}));

// The optimum of a noisy graph found from its truth: the reference a start must reach.
Se3PoseGraph OptimumFromTruth(const Se3Synthetic& s, bool sesync) {
  Se3PoseGraph reference = sesync ? ToSeSyncProblem(s.graph) : s.graph;
  for (std::size_t n = 0; n < s.truth.size(); ++n) reference.nodes[n].estimate = s.truth[n];
  EXPECT_TRUE(Optimize(reference).converged());
  return reference;
}

TEST(Se3GraphOptimizerTest, LevenbergMarquardtNeverRaisesTheCostAndFindsTheOptimum) {
  const unsigned seed = 9;
  for (const bool sesync : {false, true}) {
    Se3Synthetic s = Corkscrew(seed, 40, 0.05);
    const Se3PoseGraph reference = OptimumFromTruth(s, sesync);
    Perturb(s.graph, seed, 0.3);
    Se3PoseGraph problem = sesync ? ToSeSyncProblem(s.graph) : s.graph;
    const OptimizationResult result = Optimize(problem);
    ASSERT_GE(result.cost_history.size(), 2u);
    for (std::size_t k = 1; k < result.cost_history.size(); ++k) {
      EXPECT_LE(result.cost_history[k], result.cost_history[k - 1]) << "seed " << seed;
    }
    EXPECT_TRUE(result.converged()) << "seed " << seed;
    const double optimum = G2oChi2(reference);
    EXPECT_NEAR(result.final_cost(), optimum, 1e-5 * optimum) << "seed " << seed;
    std::vector<Eigen::Isometry3d> optimum_poses;
    for (const Se3Node& node : reference.nodes) optimum_poses.push_back(node.estimate);
    EXPECT_LT(WorstError(problem, optimum_poses).translation_m, 1e-3) << "seed " << seed;
    EXPECT_NEAR(result.final_cost(), G2oChi2(problem), 1e-9 * result.final_cost());
    if (sesync) {  // the minimized cost is SE-Sync's f of the graph as read
      Se3PoseGraph scored = s.graph;
      for (std::size_t n = 0; n < scored.nodes.size(); ++n) scored.nodes[n].estimate = problem.nodes[n].estimate;
      EXPECT_NEAR(result.final_cost(), SeSyncCost(scored), 1e-9 * result.final_cost());
    }
  }
}

TEST(Se3GraphOptimizerTest, FixedNodeHoldsTheGauge) {
  Se3Synthetic s = Corkscrew(4, 20, 0.0);
  Perturb(s.graph, 4, 0.2);
  Vector6d offset;
  offset << 0.3, -0.2, 0.1, 0.1, 0.2, -0.1;
  s.graph.nodes[0].estimate = Retract(s.truth[0], offset);  // node 0 is free this time
  s.graph.nodes[7].estimate = s.truth[7];
  s.graph.nodes[7].fixed = true;
  const OptimizationResult result = Optimize(s.graph);
  ASSERT_TRUE(result.converged());
  EXPECT_TRUE(s.graph.nodes[7].estimate.isApprox(s.truth[7], 0.0));  // untouched
  EXPECT_LT(WorstError(s.graph, s.truth).translation_m, 1e-6);  // node 0 back at the truth
  EXPECT_EQ(result.posterior.block_of_node[7], -1);
  EXPECT_EQ(result.posterior.information.rows(), 6 * (40 - 1));
}

TEST(Se3GraphOptimizerTest, UnconstrainedNodeFailsTheLinearSolve) {
  Se3Synthetic s = Corkscrew(2, 10, 0.0);
  s.graph.AddNode(Eigen::Isometry3d::Identity());  // no factor touches it
  const OptimizationResult gn = Optimize(s.graph, {.solver = Solver::kGaussNewton});
  EXPECT_EQ(gn.stop_reason, StopReason::kLinearSolveFailed);
}

TEST(Se3InitializationTest, ChordalIsExactWithoutNoise) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Se3Synthetic s = Corkscrew(seed, 25, 0.0);
    if (seed % 2 == 0) FarAndReversed(s);
    Perturb(s.graph, seed, 1.0);  // the start is forgotten, but node 0 anchors
    ASSERT_TRUE(InitializeChordal(s.graph).ok());
    const flat2d::testing::PoseError worst = WorstError(s.graph, s.truth);
    EXPECT_LT(worst.translation_m, 1e-8) << "seed " << seed;
    EXPECT_LT(worst.rotation_deg, 1e-8) << "seed " << seed;
  }
}

TEST(Se3InitializationTest, ChordalBringsANoisyGraphIntoTheBasin) {
  const unsigned seed = 21;
  Se3Synthetic s = Corkscrew(seed, 40, 0.05);
  const Se3PoseGraph reference = OptimumFromTruth(s, true);
  Perturb(s.graph, seed, 3.0);  // a start LM cannot recover from
  ASSERT_TRUE(InitializeChordal(s.graph).ok());
  EXPECT_LT(WorstError(s.graph, s.truth).rotation_deg, 10.0) << "seed " << seed;
  Se3PoseGraph problem = ToSeSyncProblem(s.graph);
  const OptimizationResult result = Optimize(problem);
  EXPECT_TRUE(result.converged());
  EXPECT_NEAR(result.final_cost(), G2oChi2(reference), 1e-5 * G2oChi2(reference)) << "seed " << seed;
}

TEST(Se3InitializationTest, OdometryChainIsExactWithoutNoiseAndBridgesBreaks) {
  Se3Synthetic s = Corkscrew(6, 20, 0.0);
  FarAndReversed(s);
  s.graph.betweens.erase(s.graph.betweens.begin() + 12);  // the edge between 12 and 13
  Perturb(s.graph, 6, 1.0);
  ASSERT_TRUE(InitializeFromOdometry(s.graph).ok());
  EXPECT_LT(WorstError(s.graph, s.truth).translation_m, 1e-9);
  s.graph.nodes.push_back({999, Eigen::Isometry3d::Identity(), false, false});
  const Status isolated = InitializeFromOdometry(s.graph);
  ASSERT_FALSE(isolated.ok());
  EXPECT_EQ(isolated.error().message, "odometry initialization: vertex 999 is not connected to vertex 0");
  // kFile falls back to the chain when a node has no vertex line.
  s.graph.nodes.pop_back();
  s.graph.nodes[5].has_estimate = false;
  s.graph.nodes[5].estimate = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(Initialize(s.graph, Initialization::kFile).ok());
  EXPECT_LT(WorstError(s.graph, s.truth).translation_m, 1e-9);
}

}  // namespace
}  // namespace flat2d::localization::graph
