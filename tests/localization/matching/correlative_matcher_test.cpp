// Acceptance (a): seeded random poses on synthetic maps (5 cm cells) are recovered within
// one cell and 0.5 deg from predictions up to 0.5 m and 5 deg off, in tracking windows and
// in a global (all headings) window.
#include "localization/matching/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "tests/localization/matching/synthetic_world.hpp"

namespace flat2d::localization {
namespace {

using testing::CastScan;
using testing::LaserModel;
using testing::World;

constexpr double kResolution = 0.05;
constexpr double kDeg = std::numbers::pi / 180.0;

Se2 Perturb(const Se2& truth, double linear, double angular, std::mt19937& random) {
  std::uniform_real_distribution<double> offset(-linear, linear);
  std::uniform_real_distribution<double> turn(-angular, angular);
  // Braces: the draws are made in order (a call's arguments have none).
  return Se2{truth.x() + offset(random), truth.y() + offset(random), truth.theta() + turn(random)};
}

struct Errors {
  double translation;
  double rotation;
};

Errors ErrorOf(const Se2& estimate, const Se2& truth) {
  return {(estimate.translation() - truth.translation()).norm(),
          std::abs(NormalizeAngle(estimate.theta() - truth.theta()))};
}

// Matches `trials` random poses of `world`; every one must be within tolerance.
void ExpectRecovered(const World& world, const LaserModel& laser, const SearchWindow& window,
                     double perturb_linear, double perturb_angular, int trials,
                     std::uint32_t seed, const MatcherLimits& limits, bool relocalize = false) {
  std::mt19937 random(seed);
  const MatchGrid map = testing::Rasterize(world, kResolution, 2.0);
  CorrelativeMatcher matcher(limits, MatcherOptions{});
  ASSERT_TRUE(matcher.SetMap(map).ok());
  std::vector<double> translations;
  std::vector<double> rotations;
  for (int trial = 0; trial < trials; ++trial) {
    const Se2 truth = testing::RandomFreePose(world, 0.5, random);
    const std::vector<Eigen::Vector2d> scan = CastScan(world, truth, laser, &random);
    const Se2 prediction = Perturb(truth, perturb_linear, perturb_angular, random);
    const MatchResult result =
        relocalize ? matcher.Relocalize(scan, prediction, window) : matcher.Match(scan, prediction, window);
    ASSERT_TRUE(result.ok()) << "seed " << seed << " trial " << trial << ": "
                             << MatchStatusName(result.status) << " score " << result.score;
    const Errors error = ErrorOf(result.map_T_vehicle, truth);
    EXPECT_LE(error.translation, kResolution)
        << "seed " << seed << " trial " << trial << " truth " << truth.Vector().transpose()
        << " got " << result.map_T_vehicle.Vector().transpose();
    EXPECT_LE(error.rotation, 0.5 * kDeg) << "seed " << seed << " trial " << trial;
    translations.push_back(error.translation);
    rotations.push_back(error.rotation);
  }
  std::sort(translations.begin(), translations.end());
  std::sort(rotations.begin(), rotations.end());
  std::printf("errors over %d poses (seed %u): median %.4f m %.3f deg, worst %.4f m %.3f deg\n",
              trials, seed, translations[translations.size() / 2],
              rotations[rotations.size() / 2] / kDeg, translations.back(), rotations.back() / kDeg);
}

TEST(CorrelativeMatcherTest, TracksRandomPosesInRooms) {
  LaserModel laser;
  laser.beams = 720;
  laser.max_range = 20.0;
  laser.noise_sigma = 0.01;
  SearchWindow window{0.6, 6.0 * kDeg};
  ExpectRecovered(testing::RoomsWorld(), laser, window, 0.5, 5.0 * kDeg, 50, 42,
                  MatcherLimits{2000, 600 * 400, 16, 512, 6});
}

TEST(CorrelativeMatcherTest, TracksRandomPosesAmongRectanglesWithAFrontLaser) {
  World world;
  world.AddBox({0.0, 0.0}, {30.0, 20.0});
  world.AddBox({5.0, 4.0}, {3.0, 2.0});
  world.AddBox({20.0, 12.0}, {2.0, 4.0});
  world.AddBox({12.0, 6.0}, {1.0, 1.0});
  // Thicker than the 0.5 m prediction error: the two faces of a 0.5 m slab are a genuine
  // ambiguity for a matcher that scores without visibility.
  world.AddBox({23.0, 3.0}, {1.5, 6.0});
  LaserModel laser;
  laser.beams = 181;
  laser.fov = std::numbers::pi;
  laser.max_range = 30.0;
  laser.noise_sigma = 0.01;
  SearchWindow window{0.6, 6.0 * kDeg};
  ExpectRecovered(world, laser, window, 0.5, 5.0 * kDeg, 50, 7,
                  MatcherLimits{2000, 800 * 600, 16, 512, 6});
}

TEST(CorrelativeMatcherTest, RelocalizesGloballyWithAllHeadings) {
  LaserModel laser;
  laser.beams = 720;
  laser.max_range = 20.0;
  SearchWindow window{4.0, std::numbers::pi};
  ExpectRecovered(testing::RoomsWorld(), laser, window, 3.0, std::numbers::pi, 5, 3,
                  MatcherLimits{800, 600 * 400, 80, 4096, 9});
}

// The two-stage relocalization finds the same poses: a coarse complete search, then a
// tracking match at full detail.
TEST(CorrelativeMatcherTest, RelocalizesInTwoStagesWithAllHeadings) {
  LaserModel laser;
  laser.beams = 720;
  laser.max_range = 20.0;
  SearchWindow window{4.0, std::numbers::pi};
  ExpectRecovered(testing::RoomsWorld(), laser, window, 3.0, std::numbers::pi, 10, 3,
                  MatcherLimits{800, 600 * 400, 80, 4096, 9}, /*relocalize=*/true);
}

TEST(CorrelativeMatcherTest, RelocalizationSearchesFewerCandidatesThanTheFineGlobalSearch) {
  const World world = testing::RoomsWorld();
  CorrelativeMatcher matcher(MatcherLimits{800, 600 * 400, 80, 4096, 9}, MatcherOptions{});
  ASSERT_TRUE(matcher.SetMap(testing::Rasterize(world, kResolution, 2.0)).ok());
  LaserModel laser;
  laser.beams = 720;
  laser.max_range = 20.0;
  const Se2 truth(4.0, 4.0, 0.3);
  const std::vector<Eigen::Vector2d> scan = CastScan(world, truth, laser);
  const Se2 prediction(6.0, 2.5, 0.3 + 2.0);
  const MatchResult fine = matcher.Match(scan, prediction, {4.0, std::numbers::pi});
  const MatchResult two_stage = matcher.Relocalize(scan, prediction, {4.0, std::numbers::pi});
  ASSERT_TRUE(fine.ok());
  ASSERT_TRUE(two_stage.ok());
  EXPECT_LE(ErrorOf(two_stage.map_T_vehicle, fine.map_T_vehicle).translation, kResolution);
  EXPECT_LT(two_stage.evaluated_candidates, fine.evaluated_candidates / 2);
  EXPECT_EQ(two_stage.points, scan.size());  // stage 2 matched the whole scan
}

TEST(CorrelativeMatcherTest, ReportsTheSearchItDid) {
  const World world = testing::RoomsWorld();
  CorrelativeMatcher matcher(MatcherLimits{2000, 600 * 400, 16, 512, 6}, MatcherOptions{});
  ASSERT_TRUE(matcher.SetMap(testing::Rasterize(world, kResolution, 2.0)).ok());
  const Se2 truth(4.0, 4.0, 0.3);
  const std::vector<Eigen::Vector2d> scan = CastScan(world, truth, LaserModel{});
  const MatchResult result = matcher.Match(scan, truth, {0.5, 3.0 * kDeg});
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.points, scan.size());
  // Olson's step for the farthest point (nearer than the 30 m cap): it moves at most one
  // cell per step.
  double max_range = 0.0;
  for (const Eigen::Vector2d& p : scan) max_range = std::max(max_range, p.norm());
  EXPECT_LE(result.angular_step * max_range, kResolution * 1.0001);
  EXPECT_EQ(result.headings, 2 * static_cast<int>(std::ceil(3.0 * kDeg / result.angular_step)) + 1);
  const std::uint64_t exhaustive = static_cast<std::uint64_t>(result.headings) * 21 * 21;
  EXPECT_LT(result.evaluated_candidates, exhaustive);
  EXPECT_GT(result.score, 0.95);
}

}  // namespace
}  // namespace flat2d::localization
