// Fixed memory: once DeadReckoning and PoseHistory exist, 10,000 updates, pushes and
// queries (inside, before and after the window, relative motions both ways, bad input)
// must not touch the heap. Counts every operator new in this test binary.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "localization/odometry/dead_reckoning.hpp"
#include "localization/odometry/pose_history.hpp"
#include "tests/localization/odometry/synthetic_drive.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::localization {
namespace {

TEST(OdometryMemory, UpdatesAndQueriesAllocateNothing) {
  constexpr int kUpdates = 10'000;
  constexpr TimeNs kPeriod = 10 * kNsPerMs;
  DeadReckoningOptions options;
  options.estimate_yaw_rate_bias = true;
  auto odometry = DeadReckoning::Create(options);
  auto history = PoseHistory::Create({.capacity = 1024, .max_extrapolation_ns = 50 * kNsPerMs});
  ASSERT_TRUE(odometry.ok() && history.ok());
  // Inputs prepared before counting: a drive with standstills, bad values and gaps.
  std::vector<hal::can::OdometryMeasurement> drive;
  drive.reserve(kUpdates);
  for (int i = 0; i < kUpdates; ++i) {
    const double v = (i / 1000) % 3 == 0 ? 0.0 : 10.0;
    const double w = 0.1 * ((i / 500) % 2 == 0 ? 1.0 : -1.0);
    drive.push_back(testing::MeasurementFor(i * kPeriod + (i % 997 == 0 ? kNsPerSecond : 0), v,
                                            w + 0.01, {.wheels = true, .yaw_rate = i % 2 == 0}));
    if (i % 101 == 0) drive.back().yaw_rate_radps = std::nan("");
  }

  const std::uint64_t before = flat2d::testing::AllocationCount();
  double checksum = 0.0;
  for (int i = 0; i < kUpdates; ++i) {
    const DeadReckoningUpdate update = odometry->Update(drive[static_cast<std::size_t>(i)]);
    if (update.new_sample()) history->Push(update.sample);
    const TimeNs newest = history->newest_ns();
    const PoseAtTime now = history->At(newest - kPeriod / 3);
    const PoseAtTime ahead = history->At(newest + 20 * kNsPerMs);
    const PoseAtTime far = history->At(newest - 20 * kNsPerSecond);
    const RelativeMotion forward = history->Between(newest - 300 * kNsPerMs, newest);
    const RelativeMotion backward = history->Between(newest, newest - 300 * kNsPerMs);
    checksum += now.local_T_vehicle.x() + ahead.covariance(0, 0) +
                static_cast<double>(far.outside_by_ns) + forward.a_T_b.y() +
                backward.covariance(2, 2);
  }
  const std::uint64_t allocations = flat2d::testing::AllocationCount() - before;

  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
  EXPECT_GT(odometry->stats().non_finite, 0u);
  EXPECT_GT(odometry->stats().gaps, 0u);
  EXPECT_GT(odometry->stats().standstill_steps, 0u);
  EXPECT_GT(odometry->stats().bias_updates, 0u);
  EXPECT_GT(history->stats().evicted, 0u);
}

}  // namespace
}  // namespace flat2d::localization
