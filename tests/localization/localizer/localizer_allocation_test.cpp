// Fixed memory (issue 9 item 4): once the localizer exists and has warmed up, hundreds of
// revolutions of tracking, map window moves, a blind spell that makes it DEGRADED and LOST,
// global relocalization and poses at odometry rate must not touch the heap, on the tracking
// thread or the map prefetch worker. Counts every operator new in this test binary.
#include <gtest/gtest.h>

#include <filesystem>

#include "localization/localizer/localizer.hpp"
#include "tests/localization/localizer/synthetic_world.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::localization {
namespace {

using testing::kOdometryNs;
using testing::kRevolutionNs;

TEST(LocalizerMemory, RevolutionsAfterWarmUpAllocateNothing) {
  constexpr int kWarmUp = 30;
  constexpr int kCounted = 300;
  const auto path = std::filesystem::temp_directory_path() / ("flat2d_localizer_memory_" + std::to_string(::getpid()) + ".f2m");
  const testing::SyntheticWorld world(path, 40.0);
  maps::ClassGrid scan = testing::SyntheticWorld::MakeScanGrid();
  auto history = PoseHistory::Create({.capacity = 4096});
  auto map = maps::PriorMapReader::Open(path, LocalizerOptions{}.map_cache_tiles);
  ASSERT_TRUE(history.ok() && map.ok());
  auto localizer = Localizer::Create(std::move(*map), {});
  ASSERT_TRUE(localizer.ok());
  localizer->SetInitialPose(0, world.TruthAt(0), Eigen::Vector3d(0.01, 0.01, 1e-4).asDiagonal());

  TimeNs next_odometry = 0;
  LocalizerState worst = LocalizerState::kLocalized;
  double checksum = 0.0;
  std::uint64_t before = 0;
  for (int k = 0; k < kWarmUp + kCounted; ++k) {
    if (k == kWarmUp) before = flat2d::testing::AllocationCount();
    for (; next_odometry <= (k + 1) * kRevolutionNs; next_odometry += kOdometryNs) {
      history->Push(world.OdometryAt(next_odometry));
      const GlobalPose pose = localizer->PoseAt(next_odometry, *history);
      checksum += pose.global_T_vehicle.x();
    }
    const bool blind = k >= 100 && k < 160;  // 6 s without structure: DEGRADED, then LOST
    const RevolutionReport report = localizer->AddGrid(world.Revolution(k, scan, blind), *history);
    if (report.state == LocalizerState::kLost) worst = LocalizerState::kLost;
  }
  const std::uint64_t allocations = flat2d::testing::AllocationCount() - before;
  std::filesystem::remove(path);

  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(worst, LocalizerState::kLost);            // the blind spell was lived through...
  EXPECT_GE(localizer->stats().relocalized, 1u);      // ... and relocalized from
  EXPECT_EQ(localizer->state(), LocalizerState::kLocalized);
  EXPECT_GT(localizer->stats().map_window_moves, 5u);
  EXPECT_GT(localizer->stats().map_prefetches_taken, 2u);  // the worker thread's fills count too
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace flat2d::localization
