// SlidingWindowGraph under bad data: (c) gross outlier matches land on the null hypothesis
// and do not move the estimate; (e) thousands of add / marginalize / solve cycles after
// warm-up allocate nothing; (f) bad input is rejected with a Status and changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "localization/graph/sliding_window.hpp"
#include "tests/localization/graph/window_drive.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::localization::graph {
namespace {

using testing::DriveOptions;
using testing::DriveStep;

SlidingWindowGraph MakeWindow(int capacity) {
  SlidingWindowOptions options;
  options.capacity = capacity;
  auto window = SlidingWindowGraph::Create(options);
  EXPECT_TRUE(window.ok());
  return std::move(window).value();
}

// Runs the drive through a window, dropping the outliers or turning them into plain
// Gaussian priors if asked; returns the newest estimate after each step.
std::vector<Se2> RunDrive(const std::vector<DriveStep>& drive, const DriveOptions& o, bool drop_outliers,
                          bool outliers_as_priors, int* null_matches_at_end = nullptr) {
  SlidingWindowGraph window = MakeWindow(50);
  std::vector<DriveStep> fed = drive;
  for (DriveStep& step : fed) {
    if (step.outlier && (drop_outliers || outliers_as_priors)) step.has_match = false;
  }
  std::vector<Se2> newest;
  for (int k = 0; k < o.nodes; ++k) {
    const bool outlier = drive[static_cast<std::size_t>(k)].has_match && drive[static_cast<std::size_t>(k)].outlier;
    const NodeId id = testing::FeedStep(window, fed, k, o);
    if (outlier && outliers_as_priors) {
      EXPECT_TRUE(window.AddPrior(id, drive[static_cast<std::size_t>(k)].match, testing::MatchInformation(o)).ok());
    }
    const auto solution = window.Solve(20);
    EXPECT_TRUE(solution.ok());
    newest.push_back(solution->newest_global_T_vehicle);
    if (null_matches_at_end) *null_matches_at_end = solution->null_matches;
  }
  if (outliers_as_priors) return newest;  // dragged poses may reject good matches too
  int outliers_in_window = 0;
  for (NodeId id = window.oldest_id(); id <= window.newest_id(); ++id) {
    const DriveStep& step = drive[static_cast<std::size_t>(id)];
    const int expected = step.has_match && step.outlier && !drop_outliers ? 1 : 0;
    outliers_in_window += expected;
    EXPECT_EQ(*window.NullMatches(id), expected) << "node " << id;
  }
  if (null_matches_at_end != nullptr) {
    EXPECT_EQ(*null_matches_at_end, outliers_in_window);
  }
  return newest;
}

TEST(SlidingWindowMaxMixture, OutlierMatchesTakeTheNullComponentAndDoNotPull) {
  DriveOptions o;
  o.nodes = std::max(120, 400 / testing::kDriveDivisor);  // > the window of 50
  o.match_every = 2;
  o.outlier_every = 5;  // 20 % of the matches are 2-10 m / up to 0.5 rad off
  std::printf("seed %u\n", o.seed);
  const std::vector<DriveStep> drive = testing::MakeDrive(o);
  int null_matches = 0;
  const std::vector<Se2> with_outliers = RunDrive(drive, o, false, false, &null_matches);
  const std::vector<Se2> clean = RunDrive(drive, o, true, false);
  const std::vector<Se2> pulled = RunDrive(drive, o, false, true);
  double worst = 0.0, worst_pulled = 0.0;
  for (std::size_t k = 0; k < clean.size(); ++k) {
    worst = std::max(worst, ComponentDifference(with_outliers[k], clean[k]).cwiseAbs().maxCoeff());
    worst_pulled = std::max(worst_pulled, ComponentDifference(pulled[k], clean[k]).cwiseAbs().maxCoeff());
  }
  std::printf("null matches in the final window %d; newest pose vs outlier-free run: worst %.2e, "
              "with outliers as Gaussians %.2e\n", null_matches, worst, worst_pulled);
  EXPECT_GE(null_matches, 3);  // and exactly the outliers in the window (RunDrive)
  // Bound: a null component has 1e-6 of the match information, so an outlier <= 11 m off
  // pulls like an inlier match <= 11 um off; a few of them cannot move a pose 0.1 mm.
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(worst_pulled, 0.1);  // the same outliers as plain Gaussians would pull it
}

TEST(SlidingWindowMemory, SteadyStateAllocatesNothing) {
  DriveOptions o;
  // Storage is sized by the capacity; the code paths are the same at 500 (the benchmark's).
  constexpr int kCapacity = testing::kDriveDivisor == 1 ? 100 : 20;
  constexpr int kWarmUp = 2 * kCapacity;  // fills the window and marginalizes as many nodes
  constexpr int kCycles = testing::kDriveDivisor == 1 ? 3000 : 200;
  o.nodes = kWarmUp + kCycles;
  o.match_every = 1;
  o.outlier_every = 7;
  const std::vector<DriveStep> drive = testing::MakeDrive(o);
  SlidingWindowGraph window = MakeWindow(kCapacity);
  for (int k = 0; k < kWarmUp; ++k) {
    testing::FeedStep(window, drive, k, o);
    ASSERT_TRUE(window.Solve(5).ok());
  }
  const std::uint64_t before = flat2d::testing::AllocationCount();
  double checksum = 0.0;
  for (int k = kWarmUp; k < o.nodes; ++k) {
    testing::FeedStep(window, drive, k, o);
    const auto solution = window.Solve(5);
    checksum += solution.ok() ? solution->newest_covariance(0, 0) : 1.0;
  }
  const std::uint64_t allocations = flat2d::testing::AllocationCount() - before;
  EXPECT_EQ(allocations, 0u) << "over " << o.nodes - kWarmUp << " add + marginalize + solve cycles";
  EXPECT_GT(checksum, 0.0);
  EXPECT_EQ(window.marginalized_count(), o.nodes - kCapacity);
}

TEST(SlidingWindowInput, OptionsAreValidated) {
  EXPECT_FALSE(SlidingWindowGraph::Create({.capacity = 1}).ok());
  EXPECT_FALSE(SlidingWindowGraph::Create({.capacity = 10, .max_between_span = 0}).ok());
  EXPECT_FALSE(SlidingWindowGraph::Create({.capacity = 10, .max_between_span = kMaxBetweenSpan + 1}).ok());
  EXPECT_FALSE(SlidingWindowGraph::Create({.capacity = 10, .max_unary_per_node = 0}).ok());
  EXPECT_FALSE(SlidingWindowGraph::Create({.capacity = 10, .step_tolerance = 0.0}).ok());
  EXPECT_TRUE(SlidingWindowGraph::Create({.capacity = 2}).ok());
}

// Two windows get the same valid input; one also gets every kind of bad input, each of
// which must fail. Afterwards both solve to bit-identical results.
TEST(SlidingWindowInput, BadInputIsRejectedAndChangesNothing) {
  DriveOptions o;
  o.nodes = 31;  // the newest node (30) has a match (every 3rd)
  const std::vector<DriveStep> drive = testing::MakeDrive(o);
  SlidingWindowGraph good = MakeWindow(10);
  SlidingWindowGraph bad = MakeWindow(10);
  EXPECT_FALSE(bad.Solve(5).ok()) << "empty window";
  for (int k = 0; k < o.nodes; ++k) {
    testing::FeedStep(good, drive, k, o);
    testing::FeedStep(bad, drive, k, o);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix3d info = testing::MatchInformation(o);
  Eigen::Matrix3d negative = info;
  negative(2, 2) = -1.0;
  Eigen::Matrix3d asymmetric = info;
  asymmetric(0, 1) = 10.0;
  Eigen::Matrix3d not_finite = info;
  not_finite(1, 1) = nan;
  const NodeId newest = bad.newest_id();
  const NodeId marginalized = bad.oldest_id() - 1;
  const Se2 pose = *bad.Estimate(newest);
  const NullHypothesis null = testing::TestNullHypothesis();
  // NaN measurements.
  EXPECT_FALSE(bad.AddMatch(newest, Se2(nan, 0.0, 0.0), info, null).ok());
  EXPECT_FALSE(bad.AddPrior(newest, Se2(0.0, 0.0, nan), info).ok());
  EXPECT_FALSE(bad.AddOdometry(newest - 1, newest, Se2(0.0, nan, 0.0), info).ok());
  // Information that is not a positive-definite symmetric matrix.
  for (const Eigen::Matrix3d& m : {negative, asymmetric, not_finite, Eigen::Matrix3d(Eigen::Matrix3d::Zero())}) {
    EXPECT_FALSE(bad.AddMatch(newest, pose, m, null).ok());
    EXPECT_FALSE(bad.AddPrior(newest, pose, m).ok());
    EXPECT_FALSE(bad.AddOdometry(newest - 1, newest, Se2(), m).ok());
  }
  // Nodes outside the window, backwards or too far.
  EXPECT_FALSE(bad.AddMatch(marginalized, pose, info, null).ok());
  EXPECT_FALSE(bad.AddMatch(newest + 1, pose, info, null).ok());
  EXPECT_FALSE(bad.AddPrior(-1, pose, info).ok());
  EXPECT_FALSE(bad.AddOdometry(marginalized, newest, Se2(), info).ok());
  EXPECT_FALSE(bad.AddOdometry(newest, newest + 1, Se2(), info).ok());
  EXPECT_FALSE(bad.AddOdometry(newest, newest - 1, Se2(), info).ok());
  EXPECT_FALSE(bad.AddOdometry(newest - 2, newest, Se2(), info).ok()) << "span 2 > max_between_span 1";
  // Null hypotheses outside (0, 1).
  EXPECT_FALSE(bad.AddMatch(newest, pose, info, {.weight = 0.0, .information_scale = 1e-6}).ok());
  EXPECT_FALSE(bad.AddMatch(newest, pose, info, {.weight = 0.1, .information_scale = 1.0}).ok());
  EXPECT_FALSE(bad.AddMatch(newest, pose, info, {.weight = nan, .information_scale = 1e-6}).ok());
  // Nodes: NaN estimate, time not after the newest.
  EXPECT_FALSE(bad.AddNode(*bad.Time(newest) + 1, Se2(nan, 0.0, 0.0)).ok());
  EXPECT_FALSE(bad.AddNode(*bad.Time(newest), pose).ok());
  EXPECT_FALSE(bad.Solve(-1).ok());
  // Full factor slots (2 unary per node: one match is there, one more fits, the third fails).
  ASSERT_TRUE(good.AddPrior(newest, pose, info).ok());
  ASSERT_TRUE(bad.AddPrior(newest, pose, info).ok());
  EXPECT_FALSE(bad.AddPrior(newest, pose, info).ok());

  EXPECT_EQ(bad.size(), good.size());
  EXPECT_EQ(bad.oldest_id(), good.oldest_id());
  const auto a = good.Solve(10);
  const auto b = bad.Solve(10);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->final_cost, b->final_cost);
  EXPECT_EQ(a->iterations, b->iterations);
  EXPECT_EQ(a->newest_global_T_vehicle.Vector(), b->newest_global_T_vehicle.Vector());
  EXPECT_EQ(a->newest_covariance, b->newest_covariance);
}

TEST(SlidingWindowInput, UnanchoredWindowFailsAndKeepsItsEstimates) {
  SlidingWindowGraph window = MakeWindow(10);
  const NodeId a = window.AddNode(1, Se2(0.0, 0.0, 0.0)).value();
  const NodeId b = window.AddNode(2, Se2(1.5, 0.0, 0.0)).value();
  ASSERT_TRUE(window.AddOdometry(a, b, Se2(1.0, 0.0, 0.0), Eigen::Matrix3d::Identity()).ok());
  EXPECT_FALSE(window.Solve(10).ok());
  EXPECT_EQ(window.Estimate(b)->x(), 1.5);
  ASSERT_TRUE(window.AddPrior(a, Se2(0.0, 0.0, 0.0), Eigen::Matrix3d::Identity()).ok());
  const auto solution = window.Solve(10);
  ASSERT_TRUE(solution.ok());
  EXPECT_NEAR(solution->newest_global_T_vehicle.x(), 1.0, 1e-9);
  EXPECT_NEAR(solution->newest_covariance(0, 0), 2.0, 1e-9);  // prior + odometry variances
}

}  // namespace
}  // namespace flat2d::localization::graph
