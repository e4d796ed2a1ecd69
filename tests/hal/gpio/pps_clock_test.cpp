#include "hal/gpio/pps_clock.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "tests/hal/gpio/pps_pulse_train.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::gpio {
namespace {

using testing::Check;
using testing::Errors;
using testing::kDriftBoundPpm;
using testing::kFirstSecond;
using testing::kJitterNs;
using testing::kOffsetBoundNs;
using testing::MakeClock;
using testing::PulseTrain;
using testing::Truth;

TEST(PpsClockTest, ConvergesOnSeededTrainsWithKnownOffsetAndDrift) {
  double max_offset = 0;
  double max_drift = 0;
  double sum_sq_offset = 0;
  constexpr int kCases = 25;
  for (int c = 0; c < kCases; ++c) {
    const std::uint32_t seed = 1000 + static_cast<std::uint32_t>(c);
    std::mt19937 rng(seed);
    Truth truth;
    // Case 0 is the documented +37 ppm crystal; the rest span both signs (inverse cases).
    truth.offset_ns = c == 0
                          ? 123'456'789
                          : std::uniform_int_distribution<TimeNs>(-450'000'000, 450'000'000)(rng);
    truth.drift_ppm = c == 0 ? 37.0 : std::uniform_real_distribution<double>(-100, 100)(rng);
    truth.jitter_ns = kJitterNs;
    PpsClock clock = MakeClock();
    PulseTrain train(truth, seed);
    constexpr std::int64_t kPulses = 60;
    for (std::int64_t k = 0; k < kPulses; ++k) {
      ASSERT_NE(clock.AddPulse(train.Pulse(k)).verdict, PulseVerdict::kSpurious)
          << "seed " << seed << " pulse " << k;
    }
    const Errors errors = Check(clock, truth, kPulses - 1);
    const PpsEstimate estimate = clock.Estimate(train.Pulse(kPulses - 1));
    std::printf(
        "seed %u: offset %+.6f ms drift %+.3f ppm -> errors %+.0f ns %+.4f ppm, "
        "jitter %.0f ns\n",
        seed, static_cast<double>(truth.offset_ns) / 1e6, truth.drift_ppm, errors.offset_ns,
        errors.drift_ppm, estimate.jitter_ns);
    EXPECT_EQ(estimate.status, PpsStatus::kLocked) << "seed " << seed;
    EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs) << "seed " << seed;
    EXPECT_LT(std::abs(errors.to_true_ns), kOffsetBoundNs) << "seed " << seed;
    EXPECT_LT(std::abs(errors.drift_ppm), kDriftBoundPpm) << "seed " << seed;
    EXPECT_GT(estimate.jitter_ns, 0.5 * kJitterNs) << "seed " << seed;
    EXPECT_LT(estimate.jitter_ns, 1.5 * kJitterNs) << "seed " << seed;
    EXPECT_EQ(estimate.counters.accepted, static_cast<std::uint64_t>(kPulses));
    max_offset = std::max(max_offset, std::abs(errors.offset_ns));
    max_drift = std::max(max_drift, std::abs(errors.drift_ppm));
    sum_sq_offset += errors.offset_ns * errors.offset_ns;
  }
  std::printf("over %d trains: offset error rms %.0f ns max %.0f ns, drift error max %.4f ppm\n",
              kCases, std::sqrt(sum_sq_offset / kCases), max_offset, max_drift);
}

TEST(PpsClockTest, ReportsStatusFromNoPpsThroughLockedToLost) {
  const Truth truth{.offset_ns = -2'500'000, .drift_ppm = 37.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 7);
  PpsClockOptions options;  // lock after 8 pulses, lost after 3 s
  PpsClock clock = MakeClock(options);
  EXPECT_EQ(clock.Estimate(0).status, PpsStatus::kNoPps);
  EXPECT_FALSE(clock.Estimate(0).valid);
  EXPECT_FALSE(clock.ToTrueTime(0).has_value());

  EXPECT_EQ(clock.AddPulse(train.Pulse(0)).verdict, PulseVerdict::kAnchored);
  EXPECT_EQ(clock.Estimate(train.Pulse(0)).status, PpsStatus::kAcquiring);
  EXPECT_FALSE(clock.Estimate(train.Pulse(0)).valid);
  for (std::int64_t k = 1; k < 7; ++k) clock.AddPulse(train.Pulse(k));
  const TimeNs seventh = train.Pulse(6);
  EXPECT_EQ(clock.Estimate(seventh).status, PpsStatus::kAcquiring);
  EXPECT_TRUE(clock.Estimate(seventh).valid);
  const TimeNs eighth = train.Pulse(7);
  clock.AddPulse(eighth);
  EXPECT_EQ(clock.Estimate(eighth).status, PpsStatus::kLocked);

  EXPECT_EQ(clock.Estimate(eighth + 2'900 * kNsPerMs).status, PpsStatus::kLocked);
  const PpsEstimate lost = clock.Estimate(eighth + 3'100 * kNsPerMs);
  EXPECT_EQ(lost.status, PpsStatus::kLost);
  EXPECT_TRUE(lost.valid) << "holdover keeps the last fit";

  // Pulses return after 10 s: acquisition restarts on the first of them.
  const PulseResult back = clock.AddPulse(train.Pulse(18));
  EXPECT_EQ(back.verdict, PulseVerdict::kAnchored);
  EXPECT_EQ(back.second, kFirstSecond + 18);
  EXPECT_EQ(clock.Estimate(train.Pulse(18)).status, PpsStatus::kAcquiring);
  EXPECT_EQ(clock.Estimate(train.Pulse(18)).counters.restarts, 1u);
  for (std::int64_t k = 19; k < 40; ++k) clock.AddPulse(train.Pulse(k));
  EXPECT_EQ(clock.Estimate(train.Pulse(39)).status, PpsStatus::kLocked);
  const Errors errors = Check(clock, truth, 39);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_EQ(clock.Estimate(train.Pulse(39)).counters.missed, 0u) << "a restart is not a miss";
}

TEST(PpsClockTest, LabelledPulsesResolveOffsetsBeyondHalfASecond) {
  // A host clock on GPS time: 18 leap seconds (and some) ahead of UTC, drifting -12 ppm.
  const Truth truth{.offset_ns = 18'123'000'000, .drift_ppm = -12.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 29);
  PpsClock clock = MakeClock();
  for (std::int64_t k = 0; k < 60; ++k) {
    ASSERT_NE(clock.AddPulse(train.Pulse(k), kFirstSecond + k).verdict, PulseVerdict::kSpurious);
    if (k == 30) {  // a repeated label (the NMEA sentence of the previous second)
      EXPECT_EQ(clock.AddPulse(train.Pulse(k) + 1'000, kFirstSecond + k).verdict,
                PulseVerdict::kSpurious);
    }
  }
  const Errors errors = Check(clock, truth, 59);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_LT(std::abs(errors.drift_ppm), kDriftBoundPpm);
  EXPECT_EQ(clock.Estimate(train.Pulse(59)).counters.spurious, 1u);
}

TEST(PpsClockTest, UnlabelledOffsetIsKnownModuloOneSecond) {
  const Truth truth{.offset_ns = 1'300'000'000, .drift_ppm = 5.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 31);
  PpsClock clock = MakeClock();
  for (std::int64_t k = 0; k < 40; ++k) clock.AddPulse(train.Pulse(k));
  // Pulses mark whole seconds only, so 1.3 s reads as 0.3 s.
  const Errors errors = Check(clock, truth, 39, /*wrap_ns=*/kNsPerSecond);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_LT(std::abs(errors.to_true_ns), kOffsetBoundNs);
}

TEST(PpsClockTest, AddPulseAndEstimateAllocateNothing) {
  const Truth truth{.offset_ns = 1'000'000, .drift_ppm = 37.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 37);
  PpsClock clock = MakeClock();
  const std::uint64_t before = flat2d::testing::AllocationCount();
  TimeNs sink = 0;
  for (std::int64_t k = 0; k < 500; ++k) {
    const TimeNs host = train.Pulse(k);
    clock.AddPulse(host);
    sink ^= clock.Estimate(host).offset_ns ^ clock.ToTrueTime(host).value_or(0);
  }
  EXPECT_EQ(flat2d::testing::AllocationCount() - before, 0u);
  EXPECT_NE(sink, 0);
}

TEST(PpsClockTest, RejectsBadOptionsNamingTheField) {
  PpsClockOptions options;
  options.window_pulses = 2;
  Result<PpsClock> clock = PpsClock::Create(options);
  ASSERT_FALSE(clock.ok());
  EXPECT_EQ(clock.error().message, "pps_clock.window_pulses must be in 3..64, got 2");
  options = {};
  options.lock_pulses = 40;
  EXPECT_EQ(PpsClock::Create(options).error().message,
            "pps_clock.lock_pulses must be in 3..window_pulses, got 40");
  options = {};
  options.residual_gate_ns = 0;
  EXPECT_FALSE(PpsClock::Create(options).ok());
  options = {};
  options.lost_timeout_ns = kNsPerSecond;
  EXPECT_FALSE(PpsClock::Create(options).ok());
}

TEST(PpsClockTest, ResetForgetsPulsesAndCounters) {
  PpsClock clock = MakeClock();
  for (std::int64_t k = 0; k < 10; ++k) clock.AddPulse((kFirstSecond + k) * kNsPerSecond);
  clock.Reset();
  const PpsEstimate estimate = clock.Estimate(kFirstSecond * kNsPerSecond);
  EXPECT_EQ(estimate.status, PpsStatus::kNoPps);
  EXPECT_EQ(estimate.counters.accepted, 0u);
  EXPECT_EQ(PpsStatusName(estimate.status), "no-pps");
}

}  // namespace
}  // namespace flat2d::hal::gpio
