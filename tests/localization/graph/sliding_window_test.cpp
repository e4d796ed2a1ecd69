// SlidingWindowGraph against ground truth and against solving without marginalization:
// (a) on a 2000-node simulated drive with outlier matches the newest pose equals the batch
// solution of the whole graph (graph_optimizer.hpp, and this solver at full capacity) and
// beats odometry alone; (b) marginalization is exact at the linearization point;
// (d) the newest covariance grows exactly as odometry propagation while matches stop and
// shrinks when they resume.
#include "localization/graph/sliding_window.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <vector>

#include "localization/graph/graph_optimizer.hpp"
#include "localization/graph/pose_graph.hpp"
#include "tests/localization/graph/window_drive.hpp"

namespace flat2d::localization::graph {
namespace {

using testing::DriveOptions;
using testing::DriveStep;

double PositionError(const Se2& a, const Se2& b) { return (a.translation() - b.translation()).norm(); }
double HeadingError(const Se2& a, const Se2& b) { return std::abs(NormalizeAngle(a.theta() - b.theta())); }

SlidingWindowGraph MakeWindow(int capacity, int span = 1, bool levenberg_marquardt = true) {
  SlidingWindowOptions options;
  options.capacity = capacity;
  options.max_between_span = span;
  options.max_between_per_node = span;
  options.levenberg_marquardt = levenberg_marquardt;
  auto window = SlidingWindowGraph::Create(options);
  EXPECT_TRUE(window.ok());
  return std::move(window).value();
}

// The whole drive up to `last` as a batch graph, initialized at `initial`.
PoseGraph BatchGraph(const std::vector<DriveStep>& drive, const std::vector<Se2>& initial, int last,
                     const DriveOptions& o) {
  PoseGraph graph;
  for (int k = 0; k <= last; ++k) {
    const DriveStep& step = drive[static_cast<std::size_t>(k)];
    const std::size_t node = graph.AddNode(initial[static_cast<std::size_t>(k)]);
    if (k == 0) graph.priors.push_back({node, step.truth, testing::InformationOf(0.1, 0.01)});
    if (k > 0) graph.betweens.push_back({node - 1, node, step.odometry, testing::OdometryInformation(o)});
    if (step.has_match) {
      const NullHypothesis null = testing::TestNullHypothesis();
      graph.mixture_priors.push_back(
          {node, step.match,
           MakeNullHypothesisMixture(testing::MatchInformation(o), null.weight, null.information_scale)});
    }
  }
  return graph;
}

TEST(SlidingWindow, NewestPoseMatchesBatchSolutionOfWholeDrive) {
  DriveOptions o;  // 2000 nodes, a match every 3rd, every 10th match a gross outlier
  o.nodes = 2000 / testing::kDriveDivisor;
  o.outlier_every = 10;
  const int first_check = o.nodes / 4 - 1;
  std::printf("seed %u, %d nodes\n", o.seed, o.nodes);
  const std::vector<DriveStep> drive = testing::MakeDrive(o);
  SlidingWindowGraph window = MakeWindow(50);
  std::vector<Se2> filtered;  // the window's newest estimate at each step
  Se2 odometry_only = drive[0].truth;
  for (int k = 0; k < o.nodes; ++k) {
    testing::FeedStep(window, drive, k, o);
    const auto solution = window.Solve(20);
    ASSERT_TRUE(solution.ok()) << solution.error().message;
    filtered.push_back(solution->newest_global_T_vehicle);
    if (k > 0) odometry_only = odometry_only * drive[static_cast<std::size_t>(k)].odometry;
    if (k != first_check && k != o.nodes - 1) continue;

    // The batch solution of nodes 0..k by the batch optimizer, from the filtered estimates.
    PoseGraph batch = BatchGraph(drive, filtered, k, o);
    const OptimizationResult result =
        Optimize(batch, {.solver = Solver::kLevenbergMarquardt, .max_iterations = 100,
                         .relative_decrease = 1e-14, .initial_lambda_scale = 1e-5});
    ASSERT_NE(result.stop_reason, StopReason::kLinearSolveFailed);
    const Se2 batch_newest = batch.nodes.back().estimate;
    const auto batch_covariance = MarginalCovariance(result.posterior, batch.nodes.size() - 1);
    ASSERT_TRUE(batch_covariance.ok());
    // The same graph in this solver without marginalization.
    SlidingWindowGraph full = MakeWindow(o.nodes);
    for (int j = 0; j <= k; ++j) {
      const DriveStep& step = drive[static_cast<std::size_t>(j)];
      const NodeId id = full.AddNode(100 * (j + 1), filtered[static_cast<std::size_t>(j)]).value();
      if (j == 0) {
        ASSERT_TRUE(full.AddPrior(id, step.truth, testing::InformationOf(0.1, 0.01)).ok());
      } else {
        ASSERT_TRUE(full.AddOdometry(id - 1, id, step.odometry, testing::OdometryInformation(o)).ok());
      }
      if (step.has_match) {
        ASSERT_TRUE(full.AddMatch(id, step.match, testing::MatchInformation(o), testing::TestNullHypothesis()).ok());
      }
    }
    const auto full_solution = full.Solve(100);
    ASSERT_TRUE(full_solution.ok());

    const Se2& newest = solution->newest_global_T_vehicle;
    const Se2& truth = drive[static_cast<std::size_t>(k)].truth;
    std::printf("k=%d window-batch %.2e m %.2e rad, window-full %.2e m, full-batch %.2e m; "
                "truth error window %.3f m, odometry %.3f m; covariance window-batch %.2e relative\n",
                k, PositionError(newest, batch_newest), HeadingError(newest, batch_newest),
                PositionError(newest, full_solution->newest_global_T_vehicle),
                PositionError(full_solution->newest_global_T_vehicle, batch_newest),
                PositionError(newest, truth), PositionError(odometry_only, truth),
                (solution->newest_covariance - *batch_covariance).norm() / batch_covariance->norm());
    // Freezing the linearization of 1950 marginalized nodes costs less than 10 um / 1 urad
    // here (matches every 3rd node keep old nodes still once they leave the window).
    EXPECT_LT(PositionError(newest, batch_newest), 1e-5);
    EXPECT_LT(HeadingError(newest, batch_newest), 1e-6);
    EXPECT_LT(PositionError(full_solution->newest_global_T_vehicle, batch_newest), 1e-6);
    EXPECT_LT(HeadingError(full_solution->newest_global_T_vehicle, batch_newest), 1e-7);
    EXPECT_LT((solution->newest_covariance - *batch_covariance).norm(), 1e-4 * batch_covariance->norm());
    EXPECT_LT((full_solution->newest_covariance - *batch_covariance).norm(), 1e-6 * batch_covariance->norm());
    // Far better than odometry alone, and consistent with its covariance (5 sigma).
    EXPECT_LT(PositionError(newest, truth), 0.1);
    EXPECT_LT(HeadingError(newest, truth), 0.01);
    if (k == o.nodes - 1) {  // odometry needs the whole drive to drift
      EXPECT_GT(PositionError(odometry_only, truth), 10.0 * PositionError(newest, truth));
    }
    for (int i = 0; i < 3; ++i) {
      const double error = i < 2 ? newest.Vector()(i) - truth.Vector()(i)
                                 : NormalizeAngle(newest.theta() - truth.theta());
      EXPECT_LT(std::abs(error), 5.0 * std::sqrt(solution->newest_covariance(i, i))) << "component " << i;
    }
  }
}

// A window of N nodes that marginalized k nodes gives the newest estimate and covariance
// of a window that never marginalized, when every factor was linearized at the same
// estimate (no Solve before the end): Schur complements are exact for the linear system.
TEST(SlidingWindow, MarginalizationIsExactAtTheLinearizationPoint) {
  DriveOptions o;
  o.nodes = 60;
  o.straight = true;
  o.match_every = 4;
  const std::vector<DriveStep> drive = testing::MakeDrive(o);
  std::mt19937 rng(7);
  std::vector<Se2> initial;
  std::vector<Se2> span_two;  // node k-2 to k, noisy (unused for k < 2)
  for (std::size_t k = 0; k < drive.size(); ++k) {
    initial.push_back(testing::AddNoise(drive[k].truth, 0.1, 0.01, rng));
    const Se2 two = drive[k < 2 ? k : k - 2].truth.Inverse() * drive[k].truth;
    span_two.push_back(testing::AddNoise(two, 0.03, 0.003, rng));
  }
  for (const int capacity : {59, 25, 10, 3}) {
    SCOPED_TRACE(capacity);
    SlidingWindowGraph never = MakeWindow(1000, 2, /*levenberg_marquardt=*/false);
    SlidingWindowGraph sliding = MakeWindow(capacity, 2, /*levenberg_marquardt=*/false);
    for (SlidingWindowGraph* window : {&never, &sliding}) {
      for (int k = 0; k < o.nodes; ++k) {
        const DriveStep& step = drive[static_cast<std::size_t>(k)];
        const NodeId id = window->AddNode(100 * (k + 1), initial[static_cast<std::size_t>(k)]).value();
        if (k == 0) {
          ASSERT_TRUE(window->AddPrior(id, step.truth, testing::InformationOf(0.1, 0.01)).ok());
        }
        if (k > 0) {
          ASSERT_TRUE(window->AddOdometry(id - 1, id, step.odometry, testing::OdometryInformation(o)).ok());
        }
        if (k > 1) {  // a second, span-2 factor: the prior then covers two nodes
          ASSERT_TRUE(window->AddOdometry(id - 2, id, span_two[static_cast<std::size_t>(k)],
                                          testing::InformationOf(0.03, 0.003)).ok());
        }
        if (step.has_match) {
          ASSERT_TRUE(window->AddMatch(id, step.match, testing::MatchInformation(o),
                                       testing::TestNullHypothesis()).ok());
        }
      }
    }
    ASSERT_EQ(sliding.marginalized_count(), o.nodes - capacity);
    const auto at_never = never.Solve(0);
    const auto at_sliding = sliding.Solve(0);
    ASSERT_TRUE(at_never.ok() && at_sliding.ok());
    // The prior holds the marginalized factors' chi-square minimized over the old nodes (M1).
    EXPECT_LE(at_sliding->initial_cost, at_never->initial_cost * (1.0 + 1e-12));
    EXPECT_LT((at_sliding->newest_covariance - at_never->newest_covariance).norm(),
              1e-6 * at_never->newest_covariance.norm());
    const auto step_never = never.Solve(1);
    const auto step_sliding = sliding.Solve(1);
    ASSERT_TRUE(step_never.ok() && step_sliding.ok());
    const Eigen::Vector3d difference = ComponentDifference(step_sliding->newest_global_T_vehicle,
                                                           step_never->newest_global_T_vehicle);
    std::printf("capacity %d: newest differs by %.2e after one step, covariance by %.2e\n", capacity,
                difference.norm(), (at_sliding->newest_covariance - at_never->newest_covariance).norm());
    EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-6);
    // The step moved the estimate (from 10 cm noise), so the comparison is not vacuous.
    EXPECT_GT(ComponentDifference(step_never->newest_global_T_vehicle, initial.back()).norm(), 1e-3);
  }
}

TEST(SlidingWindow, CovarianceGrowsWithoutMatchesAndShrinksWhenTheyResume) {
  DriveOptions o;
  o.nodes = 220;
  o.match_every = 1;
  constexpr int kGapBegin = 100;  // no matches on nodes [100, 160)
  constexpr int kGapEnd = 160;
  std::vector<DriveStep> drive = testing::MakeDrive(o);
  for (int k = kGapBegin; k < kGapEnd; ++k) drive[static_cast<std::size_t>(k)].has_match = false;
  SlidingWindowGraph window = MakeWindow(30);  // smaller than the gap: marginalizes inside it
  std::vector<double> trace;
  Eigen::Matrix3d previous_covariance = Eigen::Matrix3d::Zero();
  Se2 previous_estimate;
  for (int k = 0; k < o.nodes; ++k) {
    testing::FeedStep(window, drive, k, o);
    const auto solution = window.Solve(10);
    ASSERT_TRUE(solution.ok());
    trace.push_back(solution->newest_covariance.topLeftCorner<2, 2>().trace());
    if (k >= kGapBegin && k < kGapEnd) {
      // Exactly E5's odometry propagation from the previous newest pose.
      const Eigen::Matrix3d propagated =
          ComposeCovariance(previous_estimate, previous_covariance, drive[static_cast<std::size_t>(k)].odometry,
                            testing::OdometryInformation(o).inverse());
      EXPECT_LT((solution->newest_covariance - propagated).norm(), 1e-6 * propagated.norm()) << "node " << k;
      EXPECT_GT(trace[static_cast<std::size_t>(k)], trace[static_cast<std::size_t>(k - 1)]) << "node " << k;
    }
    previous_covariance = solution->newest_covariance;
    previous_estimate = solution->newest_global_T_vehicle;
  }
  const double before_gap = trace[kGapBegin - 1];
  const double gap_end = trace[kGapEnd - 1];
  std::printf("position covariance trace: before gap %.3e, gap end %.3e, first match %.3e, +20 %.3e\n",
              before_gap, gap_end, trace[kGapEnd], trace[kGapEnd + 20]);
  EXPECT_GT(gap_end, 10.0 * before_gap);
  EXPECT_LT(trace[kGapEnd], 0.1 * gap_end);
  EXPECT_LT(trace[kGapEnd + 20], 1.5 * before_gap);
}

}  // namespace
}  // namespace flat2d::localization::graph

namespace flat2d::localization::graph {
namespace {

// Clear empties the window and its marginal prior (a relocalized vehicle starts afresh);
// ids go on, and the cleared window needs a new anchor before it can be solved.
TEST(SlidingWindow, ClearDropsNodesFactorsAndThePriorButKeepsCounting) {
  SlidingWindowGraph window = MakeWindow(4);
  const Eigen::Matrix3d information = Eigen::Vector3d(100.0, 100.0, 1000.0).asDiagonal();
  for (int k = 0; k < 6; ++k) {  // two nodes marginalized into the prior
    const NodeId id = *window.AddNode(k + 1, Se2(Eigen::Vector2d(k, 0.0), 0.0));
    const Status added = k == 0 ? window.AddPrior(id, Se2(), information)
                                : window.AddOdometry(id - 1, id, Se2(Eigen::Vector2d(1.0, 0.0), 0.0), information);
    ASSERT_TRUE(added.ok());
  }
  ASSERT_GT(window.marginal_prior().size, 0);
  window.Clear();
  EXPECT_EQ(window.size(), 0);
  EXPECT_EQ(window.marginal_prior().size, 0);
  EXPECT_FALSE(window.Contains(5));
  EXPECT_FALSE(window.Solve(5).ok());  // empty
  const NodeId next = *window.AddNode(10, Se2(Eigen::Vector2d(3.0, 4.0), 0.5));
  EXPECT_EQ(next, 6);
  EXPECT_FALSE(window.Solve(5).ok());  // not anchored: the old prior is gone
  ASSERT_TRUE(window.AddPrior(next, Se2(Eigen::Vector2d(3.0, 4.0), 0.5), information).ok());
  auto solution = window.Solve(5);
  ASSERT_TRUE(solution.ok());
  EXPECT_NEAR(solution->newest_global_T_vehicle.x(), 3.0, 1e-9);
  EXPECT_NEAR(solution->newest_covariance(0, 0), 0.01, 1e-9);  // the prior alone
}

}  // namespace
}  // namespace flat2d::localization::graph
