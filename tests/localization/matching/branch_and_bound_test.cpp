// Acceptance (c): branch and bound returns exactly the pose and score of the exhaustive
// search of the same window, over many random cases: matching and non-matching scans,
// windows of one coarsest block and of many, tracking and full-circle headings.
#include "localization/matching/branch_and_bound.hpp"

#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "localization/matching/correlative_matcher.hpp"
#include "tests/localization/matching/synthetic_world.hpp"

namespace flat2d::localization {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Case {
  MatcherLimits limits;
  SearchWindow window;
  double angular_step;
};

void ExpectSameAsExhaustive(const Case& c, std::uint32_t seed, int trials, bool random_scan) {
  std::mt19937 random(seed);
  const testing::World world = testing::RoomsWorld();
  MatcherOptions options;
  options.angular_step = c.angular_step;
  options.min_score = 0.0;
  CorrelativeMatcher matcher(c.limits, options);
  ASSERT_TRUE(matcher.SetMap(testing::Rasterize(world, 0.05, 1.0)).ok());
  testing::LaserModel laser;
  laser.beams = 90;
  laser.noise_sigma = 0.03;
  std::uniform_real_distribution<double> offset(-0.4, 0.4);
  std::uniform_real_distribution<double> scatter(-8.0, 8.0);
  std::uint64_t evaluated_bnb = 0;
  std::uint64_t evaluated_exhaustive = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const Se2 truth = testing::RandomFreePose(world, 0.3, random);
    std::vector<Eigen::Vector2d> scan = testing::CastScan(world, truth, laser, &random);
    if (random_scan) {
      for (Eigen::Vector2d& p : scan) p = {scatter(random), scatter(random)};
    }
    // Braces: the draws are made in order (a call's arguments have none).
    const Se2 prediction{truth.x() + offset(random), truth.y() + offset(random),
                         truth.theta() + 10.0 * offset(random) * kDeg};
    const MatchResult fast = matcher.Match(scan, prediction, c.window);
    const MatchResult slow = matcher.MatchExhaustive(scan, prediction, c.window);
    ASSERT_EQ(fast.status, slow.status) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.score, slow.score) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.map_T_vehicle.x(), slow.map_T_vehicle.x()) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.map_T_vehicle.y(), slow.map_T_vehicle.y()) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.map_T_vehicle.theta(), slow.map_T_vehicle.theta())
        << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.headings, slow.headings);
    evaluated_bnb += fast.evaluated_candidates;
    evaluated_exhaustive += slow.evaluated_candidates;
  }
  std::printf("seed %u: branch and bound scored %llu nodes, exhaustive %llu candidates\n", seed,
              static_cast<unsigned long long>(evaluated_bnb),
              static_cast<unsigned long long>(evaluated_exhaustive));
}

TEST(BranchAndBoundTest, SameAsExhaustiveWithOneRootPerHeading) {
  const Case c{MatcherLimits{200, 500 * 400, 16, 64, 6}, SearchWindow{0.3, 2.0 * kDeg}, 0.5 * kDeg};
  ExpectSameAsExhaustive(c, 1, 100, /*random_scan=*/false);
}

TEST(BranchAndBoundTest, SameAsExhaustiveWithManyRootsPerHeading) {
  // Three levels (blocks of 4 cells) tile a 21-cell window with 36 roots per heading.
  const Case c{MatcherLimits{200, 500 * 400, 16, 64, 3}, SearchWindow{0.5, 2.0 * kDeg}, 0.5 * kDeg};
  ExpectSameAsExhaustive(c, 2, 100, /*random_scan=*/false);
}

TEST(BranchAndBoundTest, SameAsExhaustiveForScansThatFitNowhere) {
  // Random points: flat surfaces full of ties, the hardest case for tie-breaking.
  const Case c{MatcherLimits{200, 500 * 400, 16, 64, 5}, SearchWindow{0.4, 1.5 * kDeg}, 0.5 * kDeg};
  ExpectSameAsExhaustive(c, 3, 100, /*random_scan=*/true);
}

TEST(BranchAndBoundTest, SameAsExhaustiveOverAllHeadings) {
  const Case c{MatcherLimits{200, 500 * 400, 16, 128, 4}, SearchWindow{0.25, std::numbers::pi},
               5.0 * kDeg};
  ExpectSameAsExhaustive(c, 4, 30, /*random_scan=*/false);
}

TEST(BranchAndBoundTest, RootCountCoversTheWindow) {
  EXPECT_EQ(BranchAndBound::RootCount(10, 30, 7), 10u);       // 61 cells in one 64 block
  EXPECT_EQ(BranchAndBound::RootCount(10, 30, 6), 40u);       // 2 x 2 blocks of 32
  EXPECT_EQ(BranchAndBound::RootCount(1, 0, 1), 1u);
}

}  // namespace
}  // namespace flat2d::localization
