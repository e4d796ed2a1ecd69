// Acceptance (f): after construction, loading a map and matching allocate nothing.
#include <numbers>

#include <gtest/gtest.h>

#include "localization/matching/correlative_matcher.hpp"
#include "localization/matching/scan_points.hpp"
#include "tests/localization/matching/synthetic_world.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::localization {
namespace {

TEST(MatcherAllocationTest, SetMapAndMatchAllocateNothing) {
  const testing::World world = testing::RoomsWorld();
  const MatchGrid map = testing::Rasterize(world, 0.05, 1.0);
  testing::LaserModel laser;
  laser.beams = 1440;
  const std::vector<Eigen::Vector2d> raw = testing::CastScan(world, Se2(4.0, 4.0, 0.3), laser);
  CorrelativeMatcher matcher(MatcherLimits{2000, 600 * 400, 40, 4096, 8}, MatcherOptions{});
  ScanPoints scan(2000);

  const std::uint64_t before = flat2d::testing::AllocationCount();
  ASSERT_TRUE(matcher.SetMap(map).ok());
  scan.Clear();
  for (const Eigen::Vector2d& p : raw) scan.Add(p);
  scan.VoxelDecimate(0.1);
  const MatchResult tracking = matcher.Match(scan.points(), Se2(4.2, 3.9, 0.35), {1.5, 0.1});
  const MatchResult global = matcher.Match(scan.points(), Se2(5.0, 5.0, 0.0), {2.0, 3.2});
  const MatchResult exhaustive =
      matcher.MatchExhaustive(scan.points(), Se2(4.0, 4.0, 0.3), {0.1, 0.01});
  const MatchResult failed = matcher.Match({}, Se2(4.0, 4.0, 0.3), {1.5, 0.1});
  const MatchResult relocalized = matcher.Relocalize(scan.points(), Se2(5.0, 5.0, 0.0), {2.0, 3.2});
  EXPECT_EQ(flat2d::testing::AllocationCount(), before);
  EXPECT_TRUE(relocalized.ok());
  EXPECT_TRUE(tracking.ok());
  EXPECT_TRUE(global.ok());
  EXPECT_TRUE(exhaustive.ok());
  EXPECT_EQ(failed.status, MatchStatus::kTooFewPoints);
}

}  // namespace
}  // namespace flat2d::localization
