// Acceptance (d): the covariance comes from the score surface, so it is large along
// directions the scene does not constrain and small across them.
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "localization/matching/correlative_matcher.hpp"
#include "tests/localization/matching/synthetic_world.hpp"

namespace flat2d::localization {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

MatchResult MatchIn(const testing::World& world, const Se2& truth, double max_range) {
  CorrelativeMatcher matcher(MatcherLimits{2000, 1400 * 1400, 16, 256, 6}, MatcherOptions{});
  EXPECT_TRUE(matcher.SetMap(testing::Rasterize(world, 0.05, 1.0)).ok());
  testing::LaserModel laser;
  laser.beams = 720;
  laser.max_range = max_range;
  const std::vector<Eigen::Vector2d> scan = testing::CastScan(world, truth, laser);
  return matcher.Match(scan, truth, {0.5, 3.0 * kDeg});
}

// A corridor rotated by `axis` whose ends are out of the laser's reach.
testing::World RotatedCorridor(double axis) {
  testing::World straight = testing::CorridorWorld(60.0, 2.0);
  testing::World world;
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(axis).toRotationMatrix();
  for (const testing::Segment& wall : straight.walls) {
    world.AddWall(rotation * wall.a + Eigen::Vector2d(40.0, 40.0),
                  rotation * wall.b + Eigen::Vector2d(40.0, 40.0));
  }
  return world;
}

TEST(CovarianceTest, CorridorIsUncertainAlongItsAxisOnly) {
  for (const double axis : {0.0, 30.0 * kDeg, 90.0 * kDeg}) {
    const MatchResult result = MatchIn(RotatedCorridor(axis), Se2(40.0, 40.0, axis + 0.2), 8.0);
    ASSERT_TRUE(result.ok()) << MatchStatusName(result.status);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(
        result.covariance.topLeftCorner<2, 2>());
    const double across = solver.eigenvalues()(0);
    const double along = solver.eigenvalues()(1);
    const Eigen::Vector2d direction = solver.eigenvectors().col(1);
    std::printf("corridor at %.0f deg: std along %.4f m, across %.4f m\n", axis / kDeg,
                std::sqrt(along), std::sqrt(across));
    EXPECT_GT(along, 25.0 * across) << "axis " << axis / kDeg;
    // The uncertain direction is the corridor's axis (within 5 deg).
    EXPECT_GT(std::abs(direction.dot(Eigen::Vector2d(std::cos(axis), std::sin(axis)))),
              std::cos(5.0 * kDeg));
    EXPECT_LT(std::sqrt(across), 0.03);
  }
}

TEST(CovarianceTest, CornerIsWellConstrainedInEveryDirection) {
  const MatchResult result = MatchIn(testing::CornerWorld(10.0), Se2(3.0, 2.5, 0.7), 15.0);
  ASSERT_TRUE(result.ok()) << MatchStatusName(result.status);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(
      result.covariance.topLeftCorner<2, 2>());
  std::printf("corner: std %.4f and %.4f m, heading %.3f deg\n", std::sqrt(solver.eigenvalues()(0)),
              std::sqrt(solver.eigenvalues()(1)), std::sqrt(result.covariance(2, 2)) / kDeg);
  EXPECT_LT(std::sqrt(solver.eigenvalues()(1)), 0.03);
  EXPECT_LT(solver.eigenvalues()(1), 4.0 * solver.eigenvalues()(0));
  EXPECT_LT(std::sqrt(result.covariance(2, 2)), 0.5 * kDeg);
  // Symmetric and positive definite: usable as a factor's covariance.
  EXPECT_TRUE(result.covariance.isApprox(result.covariance.transpose()));
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(result.covariance).eigenvalues()(0), 0.0);
}

TEST(CovarianceTest, CorridorIsConstrainedOnceItsEndIsInView) {
  // The same corridor seen from 3 m before its closed end: now along the axis is known too.
  testing::World world = testing::CorridorWorld(60.0, 2.0);
  world.AddWall({30.0, -1.0}, {30.0, 1.0});
  const MatchResult open = MatchIn(world, Se2(0.0, 0.0, 0.1), 8.0);
  const MatchResult closed = MatchIn(world, Se2(27.0, 0.0, 0.1), 8.0);
  ASSERT_TRUE(open.ok());
  ASSERT_TRUE(closed.ok());
  EXPECT_LT(closed.covariance(0, 0), 0.05 * open.covariance(0, 0));
}

}  // namespace
}  // namespace flat2d::localization
