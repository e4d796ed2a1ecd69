// PoseHistory: interpolation at arbitrary times against the closed form (geodesic
// interpolation is exact on a constant arc), answers outside the window, the ring, and
// the relative motion between two times with its covariance.
#include "localization/odometry/pose_history.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "localization/odometry/dead_reckoning.hpp"
#include "tests/localization/odometry/synthetic_drive.hpp"

namespace flat2d::localization {
namespace {

using testing::ClosedFormArc;
using testing::Seconds;

constexpr unsigned kSeed = 4242;
constexpr double kV = 10.0;
constexpr double kW = 0.2;
constexpr TimeNs kStart = 1'700'000'000 * kNsPerSecond;  // absolute times, as on a vehicle
constexpr TimeNs kPeriod = 20 * kNsPerMs;                // 50 Hz

// A constant arc from kStart for `seconds`, dead reckoned into a history.
PoseHistory ArcHistory(double seconds, PoseHistoryOptions options = {}) {
  auto history = PoseHistory::Create(options);
  auto odometry = DeadReckoning::Create({});
  EXPECT_TRUE(history.ok() && odometry.ok());
  for (auto m : testing::SampleDrive({{kV, kW, seconds}}, 50.0, {})) {
    m.time_ns += kStart;
    EXPECT_TRUE(history->Push(odometry->Update(m).sample));
  }
  return std::move(history.value());
}

Se2 Truth(TimeNs time_ns) { return ClosedFormArc(kV, kW, Seconds(time_ns - kStart)); }

TEST(PoseHistory, InterpolationAtArbitraryTimesMatchesTheClosedForm) {
  const PoseHistory history = ArcHistory(20.0);
  std::printf("  seed %u\n", kSeed);
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<TimeNs> offset(0, 20 * kNsPerSecond);
  double worst_position = 0.0;
  double worst_heading = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const TimeNs t = kStart + offset(rng);
    const PoseAtTime pose = history.At(t);
    ASSERT_EQ(pose.status, QueryStatus::kInWindow);
    worst_position =
        std::max(worst_position, testing::PositionError(pose.local_T_vehicle, Truth(t)));
    worst_heading = std::max(worst_heading, testing::HeadingError(pose.local_T_vehicle, Truth(t)));
  }
  std::printf("  1000 queries over 200 m: max position error %.3g m, heading %.3g rad\n",
              worst_position, worst_heading);
  EXPECT_LT(worst_position, 1e-6);
  EXPECT_LT(worst_heading, 1e-9);
}

TEST(PoseHistory, CovarianceIsContinuousAndGrowsBetweenSamples) {
  const PoseHistory history = ArcHistory(2.0);
  const TimeNs t0 = kStart + 50 * kPeriod;
  const Eigen::Matrix3d at_sample = history.At(t0).covariance;
  const Eigen::Matrix3d at_next = history.At(t0 + kPeriod).covariance;
  // 1 ns is 5e-8 of a step, whose covariance is ~2 % of the pose's here.
  EXPECT_LT((history.At(t0 + 1).covariance - at_sample).norm(), 1e-8 * at_sample.norm());
  EXPECT_LT((history.At(t0 + kPeriod - 1).covariance - at_next).norm(), 1e-8 * at_next.norm());
  double previous_trace = at_sample.trace();
  for (TimeNs dt = kPeriod / 4; dt <= kPeriod; dt += kPeriod / 4) {
    const double trace = history.At(t0 + dt).covariance.trace();
    EXPECT_GT(trace, previous_trace);
    previous_trace = trace;
  }
}

TEST(PoseHistory, TimesOutsideTheWindowSayWhereAndHowFar) {
  auto empty = PoseHistory::Create({});
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(empty->At(kStart).status, QueryStatus::kEmpty);
  EXPECT_EQ(empty->Between(kStart, kStart).status, QueryStatus::kEmpty);

  const PoseHistory history = ArcHistory(2.0);  // 50 ms extrapolation by default
  const TimeNs newest = kStart + 2 * kNsPerSecond;
  EXPECT_EQ(history.oldest_ns(), kStart);
  EXPECT_EQ(history.newest_ns(), newest);
  const PoseAtTime before = history.At(kStart - 7 * kNsPerMs);
  EXPECT_EQ(before.status, QueryStatus::kBeforeWindow);
  EXPECT_EQ(before.outside_by_ns, 7 * kNsPerMs);
  EXPECT_FALSE(before.ok());
  const PoseAtTime after = history.At(newest + 51 * kNsPerMs);
  EXPECT_EQ(after.status, QueryStatus::kAfterWindow);
  EXPECT_EQ(after.outside_by_ns, 51 * kNsPerMs);
  EXPECT_EQ(history.At(newest).status, QueryStatus::kInWindow);
  EXPECT_EQ(history.At(kStart).status, QueryStatus::kInWindow);

  const RelativeMotion refused = history.Between(kStart + kNsPerSecond, kStart - 3);
  EXPECT_EQ(refused.status, QueryStatus::kBeforeWindow);
  EXPECT_EQ(refused.outside_by_ns, 3);
}

TEST(PoseHistory, ShortExtrapolationContinuesTheLastStep) {
  const PoseHistory history = ArcHistory(2.0);
  const TimeNs t = kStart + 2 * kNsPerSecond + 37 * kNsPerMs;
  const PoseAtTime pose = history.At(t);
  ASSERT_EQ(pose.status, QueryStatus::kExtrapolated);
  EXPECT_EQ(pose.outside_by_ns, 37 * kNsPerMs);
  EXPECT_LT(testing::PositionError(pose.local_T_vehicle, Truth(t)), 1e-6);  // constant arc
  EXPECT_GT(pose.covariance.trace(), history.At(history.newest_ns()).covariance.trace());

  auto none = ArcHistory(2.0, {.capacity = 4096, .max_extrapolation_ns = 0});
  EXPECT_EQ(none.At(t).status, QueryStatus::kAfterWindow);
}

TEST(PoseHistory, NoExtrapolationAcrossADiscontinuity) {
  PoseHistory history = ArcHistory(1.0);
  OdometrySample held;
  held.time_ns = history.newest_ns() + kNsPerSecond;
  held.local_T_vehicle = history.At(history.newest_ns()).local_T_vehicle;
  held.discontinuity = true;
  ASSERT_TRUE(history.Push(held));
  EXPECT_EQ(history.At(held.time_ns + kNsPerMs).status, QueryStatus::kAfterWindow);
  EXPECT_TRUE(history.Between(kStart, held.time_ns).spans_discontinuity);
  EXPECT_TRUE(history.Between(held.time_ns - 1, held.time_ns).spans_discontinuity);
  EXPECT_FALSE(history.Between(kStart, held.time_ns - kNsPerSecond).spans_discontinuity);
}

TEST(PoseHistory, RingKeepsTheNewestSamplesAndRefusesOlderOnes) {
  PoseHistory history = ArcHistory(4.0, {.capacity = 100, .max_extrapolation_ns = 0});
  EXPECT_EQ(history.size(), 100u);
  EXPECT_EQ(history.stats().evicted, 201u - 100u);
  EXPECT_EQ(history.oldest_ns(), kStart + 101 * kPeriod);
  EXPECT_EQ(history.At(kStart + 100 * kPeriod).status, QueryStatus::kBeforeWindow);
  const TimeNs t = kStart + 150 * kPeriod + 3 * kNsPerMs;
  EXPECT_LT(testing::PositionError(history.At(t).local_T_vehicle, Truth(t)), 1e-6);

  OdometrySample stale;
  stale.time_ns = history.newest_ns();
  EXPECT_FALSE(history.Push(stale));
  EXPECT_EQ(history.stats().not_newer, 1u);
  history.Clear();
  EXPECT_EQ(history.At(t).status, QueryStatus::kEmpty);
}

TEST(PoseHistory, RelativeMotionMatchesTheClosedFormInBothDirections) {
  const PoseHistory history = ArcHistory(20.0);
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<TimeNs> offset(0, 20 * kNsPerSecond + 50 * kNsPerMs);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    const TimeNs a = kStart + offset(rng);
    const TimeNs b = kStart + offset(rng);
    const RelativeMotion ab = history.Between(a, b);
    const RelativeMotion ba = history.Between(b, a);
    ASSERT_TRUE(ab.ok() && ba.ok());
    const Se2 expected = Truth(a).Inverse() * Truth(b);
    worst = std::max(worst, ComponentDifference(ab.a_T_b, expected).norm());
    EXPECT_LT(ComponentDifference(ab.a_T_b * ba.a_T_b, Se2()).norm(), 1e-9);
    // ba's covariance is ab's mapped through the inverse (se2.hpp E6).
    const Eigen::Matrix3d j = InverseJacobian(ab.a_T_b);
    EXPECT_LT((j * ab.covariance * j.transpose() - ba.covariance).norm(),
              1e-9 * (1.0 + ab.covariance.norm()));
  }
  std::printf("  200 pairs: max error %.3g\n", worst);
  EXPECT_LT(worst, 1e-6);
}

// From the first sample (zero covariance) the chained covariance is the absolute one;
// between later times it is what the steps in between add, independent of the start.
TEST(PoseHistory, RelativeCovarianceCountsOnlyTheStepsInBetween) {
  const PoseHistory history = ArcHistory(10.0);
  const TimeNs t = kStart + 7 * kNsPerSecond + 3 * kNsPerMs;
  const Eigen::Matrix3d absolute = history.At(t).covariance;
  EXPECT_LT((history.Between(kStart, t).covariance - absolute).norm(), 1e-12 * absolute.norm());
  const RelativeMotion early =
      history.Between(kStart + 1 * kNsPerSecond, kStart + 2 * kNsPerSecond);
  const RelativeMotion late = history.Between(kStart + 8 * kNsPerSecond, kStart + 9 * kNsPerSecond);
  // A constant arc: equal intervals have equal motion and covariance, wherever they lie.
  EXPECT_LT((early.covariance - late.covariance).norm(), 1e-9 * early.covariance.norm());
  EXPECT_EQ(history.Between(t, t).covariance, Eigen::Matrix3d::Zero());
}

TEST(PoseHistoryOptions, ValidationNamesTheField) {
  const auto small = PoseHistory::Create({.capacity = 1});
  ASSERT_FALSE(small.ok());
  EXPECT_NE(small.error().message.find("capacity"), std::string::npos);
  EXPECT_FALSE(ValidateOptions(PoseHistoryOptions{.capacity = 8, .max_extrapolation_ns = -1}).ok());
}

}  // namespace
}  // namespace flat2d::localization
