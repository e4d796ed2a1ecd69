// Acceptance (e): bad input ends in a failure status that says why, never a crash.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "localization/matching/correlative_matcher.hpp"
#include "tests/localization/matching/synthetic_world.hpp"

namespace flat2d::localization {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

class BadInputTest : public ::testing::Test {
 protected:
  BadInputTest() : matcher_(MatcherLimits{1000, 600 * 400, 16, 256, 6}, MatcherOptions{}) {
    EXPECT_TRUE(matcher_.SetMap(testing::Rasterize(world_, 0.05, 1.0)).ok());
    scan_ = testing::CastScan(world_, truth_, testing::LaserModel{});
  }

  testing::World world_ = testing::RoomsWorld();
  Se2 truth_{4.0, 4.0, 0.3};
  CorrelativeMatcher matcher_;
  std::vector<Eigen::Vector2d> scan_;
  SearchWindow window_{0.5, 5.0 * kDeg};
};

TEST_F(BadInputTest, GoodInputMatches) {
  EXPECT_EQ(matcher_.Match(scan_, truth_, window_).status, MatchStatus::kOk);
}

TEST_F(BadInputTest, EmptyAndTinyScansHaveTooFewPoints) {
  EXPECT_EQ(matcher_.Match({}, truth_, window_).status, MatchStatus::kTooFewPoints);
  const std::vector<Eigen::Vector2d> three(scan_.begin(), scan_.begin() + 3);
  EXPECT_EQ(matcher_.Match(three, truth_, window_).status, MatchStatus::kTooFewPoints);
}

TEST_F(BadInputTest, NonFinitePointsOrPredictionsAreInvalid) {
  std::vector<Eigen::Vector2d> scan = scan_;
  scan[17].x() = std::nan("");
  EXPECT_EQ(matcher_.Match(scan, truth_, window_).status, MatchStatus::kInvalidInput);
  scan[17].x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(matcher_.Match(scan, truth_, window_).status, MatchStatus::kInvalidInput);
  EXPECT_EQ(matcher_.Match(scan_, Se2(std::nan(""), 4.0, 0.0), window_).status,
            MatchStatus::kInvalidInput);
  EXPECT_EQ(matcher_.Match(scan_, truth_, {std::nan(""), 0.1}).status, MatchStatus::kInvalidInput);
  EXPECT_EQ(matcher_.Match(scan_, truth_, {-1.0, 0.1}).status, MatchStatus::kInvalidInput);
}

TEST_F(BadInputTest, LimitsAreRefusedNotExceeded) {
  EXPECT_EQ(matcher_.Match(scan_, truth_, {5.0, 0.1}).status, MatchStatus::kInvalidInput);
  const std::vector<Eigen::Vector2d> many(2000, Eigen::Vector2d(1.0, 0.0));
  EXPECT_EQ(matcher_.Match(many, truth_, window_).status, MatchStatus::kInvalidInput);
  CorrelativeMatcher small(MatcherLimits{100, 100, 4, 8, 2}, MatcherOptions{});
  EXPECT_FALSE(small.SetMap(testing::Rasterize(world_, 0.05, 1.0)).ok());
  EXPECT_EQ(small.Match(scan_, truth_, window_).status, MatchStatus::kNoMap);
}

TEST_F(BadInputTest, PredictionOffTheMapIsOutsideTheMap) {
  EXPECT_EQ(matcher_.Match(scan_, Se2(-50.0, 4.0, 0.0), window_).status, MatchStatus::kOutsideMap);
  EXPECT_EQ(matcher_.Match(scan_, Se2(1e300, -1e300, 0.0), window_).status,
            MatchStatus::kOutsideMap);
}

TEST_F(BadInputTest, ScanThatLandsOffTheMapScoresBelowThreshold) {
  std::vector<Eigen::Vector2d> far = scan_;
  for (Eigen::Vector2d& p : far) p += Eigen::Vector2d(500.0, 1e12);
  const MatchResult result = matcher_.Match(far, truth_, window_);
  EXPECT_EQ(result.status, MatchStatus::kScoreBelowThreshold);
  EXPECT_EQ(result.score, 0.0);
}

TEST_F(BadInputTest, RepeatedStructureIsAmbiguousWhenAsked) {
  MatcherOptions options;
  options.ambiguity_ratio = 0.9;
  CorrelativeMatcher matcher(MatcherLimits{1000, 1400 * 200, 16, 256, 6}, options);
  const testing::World corridor = testing::CorridorWorld(60.0, 2.0);
  ASSERT_TRUE(matcher.SetMap(testing::Rasterize(corridor, 0.05, 1.0)).ok());
  testing::LaserModel laser;
  laser.max_range = 8.0;
  const Se2 truth(0.0, 0.0, 0.0);
  const MatchResult result = matcher.Match(testing::CastScan(corridor, truth, laser), truth, window_);
  EXPECT_EQ(result.status, MatchStatus::kAmbiguous);
  EXPECT_GE(result.second_peak_score, 0.9 * result.score);
}

}  // namespace
}  // namespace flat2d::localization
