// PpsClock against missed, spurious and misplaced pulses, and host clock steps.
#include "hal/gpio/pps_clock.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <vector>

#include "tests/hal/gpio/pps_pulse_train.hpp"

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

TEST(PpsClockTest, CountsMissedPulsesAndStillConverges) {
  const Truth truth{.offset_ns = 87'654'321, .drift_ppm = 37.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 11);
  PpsClockOptions options;
  options.lost_timeout_ns = 5 * kNsPerSecond;  // the longest gap below is 4 s
  PpsClock clock = MakeClock(options);
  const std::set<std::int64_t> dropped = {10, 20, 21, 30, 31, 32, 45};
  for (std::int64_t k = 0; k < 60; ++k) {
    const TimeNs host = train.Pulse(k);  // drawn for dropped pulses too, to keep the noise
    if (dropped.contains(k)) continue;
    const PulseResult result = clock.AddPulse(host);
    ASSERT_NE(result.verdict, PulseVerdict::kSpurious) << "pulse " << k;
    EXPECT_EQ(result.second, kFirstSecond + k);
    if (k == 22) {
      EXPECT_EQ(result.missed, 2);
    }
    if (k == 33) {
      EXPECT_EQ(result.missed, 3);
    }
  }
  const PpsEstimate estimate = clock.Estimate(train.Pulse(59));
  EXPECT_EQ(estimate.counters.missed, dropped.size());
  EXPECT_EQ(estimate.counters.spurious, 0u);
  EXPECT_EQ(estimate.counters.restarts, 0u);
  EXPECT_EQ(estimate.status, PpsStatus::kLocked);
  const Errors errors = Check(clock, truth, 59);
  std::printf("missed pulses: offset error %+.0f ns, drift error %+.4f ppm\n", errors.offset_ns,
              errors.drift_ppm);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_LT(std::abs(errors.drift_ppm), kDriftBoundPpm);
}

TEST(PpsClockTest, RejectsSpuriousPulsesWithoutDisturbingTheFit) {
  const Truth truth{.offset_ns = -301'000'000, .drift_ppm = -64.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 13);
  PpsClock clock = MakeClock();
  std::uint64_t injected = 0;
  for (std::int64_t k = 0; k < 60; ++k) {
    const TimeNs host = train.Pulse(k);
    ASSERT_NE(clock.AddPulse(host).verdict, PulseVerdict::kSpurious) << "pulse " << k;
    // Glitches, at most two in a row (three would restart acquisition): 0.3 s and 0.73 s
    // into the second (intervals far from 1 s), and a contact bounce 20 us after a pulse.
    std::vector<TimeNs> glitches;
    if (k % 7 == 3) glitches = {300 * kNsPerMs, 20'000};
    if (k % 7 == 5) glitches = {730 * kNsPerMs};
    for (const TimeNs after : glitches) {
      EXPECT_EQ(clock.AddPulse(host + after).verdict, PulseVerdict::kSpurious) << k;
      ++injected;
    }
    // A pulse 400 us late: an interval of almost exactly 1 s, but off the fit.
    if (k == 40) {
      const TimeNs late = train.Pulse(41) + 400'000;
      EXPECT_EQ(clock.AddPulse(late).verdict, PulseVerdict::kSpurious);
      ++injected;
    }
  }
  const PpsEstimate estimate = clock.Estimate(train.Pulse(59));
  EXPECT_EQ(estimate.counters.spurious, injected);
  EXPECT_EQ(estimate.counters.accepted, 60u);
  EXPECT_EQ(estimate.counters.restarts, 0u);
  EXPECT_EQ(estimate.status, PpsStatus::kLocked);
  const Errors errors = Check(clock, truth, 59);
  std::printf("%llu spurious pulses: offset error %+.0f ns, drift error %+.4f ppm\n",
              static_cast<unsigned long long>(injected), errors.offset_ns, errors.drift_ppm);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_LT(std::abs(errors.drift_ppm), kDriftBoundPpm);
}

TEST(PpsClockTest, RecoversFromASpuriousFirstPulse) {
  const Truth truth{.offset_ns = 123'000'000, .drift_ppm = 37.0, .jitter_ns = kJitterNs};
  PulseTrain train(truth, 17);
  PpsClock clock = MakeClock();  // restarts after 3 rejects in a row
  EXPECT_EQ(clock.AddPulse(train.Pulse(0) - 370 * kNsPerMs).verdict, PulseVerdict::kAnchored);
  EXPECT_EQ(clock.AddPulse(train.Pulse(1)).verdict, PulseVerdict::kSpurious);
  EXPECT_EQ(clock.AddPulse(train.Pulse(2)).verdict, PulseVerdict::kSpurious);
  EXPECT_EQ(clock.AddPulse(train.Pulse(3)).verdict, PulseVerdict::kAnchored);
  for (std::int64_t k = 4; k < 60; ++k) {
    ASSERT_EQ(clock.AddPulse(train.Pulse(k)).verdict, PulseVerdict::kAccepted) << k;
  }
  const PpsEstimate estimate = clock.Estimate(train.Pulse(59));
  EXPECT_EQ(estimate.counters.restarts, 1u);
  EXPECT_EQ(estimate.counters.spurious, 2u);
  EXPECT_EQ(estimate.status, PpsStatus::kLocked);
  EXPECT_LT(std::abs(Check(clock, truth, 59).offset_ns), kOffsetBoundNs);
}

TEST(PpsClockTest, FollowsAHostClockStepAfterReacquiring) {
  const Truth before{.offset_ns = 5'000'000, .drift_ppm = 12.0, .jitter_ns = kJitterNs};
  Truth after = before;
  after.offset_ns += 200 * kNsPerMs;  // NTP stepped the host clock 0.2 s forward
  PulseTrain train_before(before, 19);
  PulseTrain train_after(after, 23);
  PpsClock clock = MakeClock();
  for (std::int64_t k = 0; k < 40; ++k) clock.AddPulse(train_before.Pulse(k));
  for (std::int64_t k = 40; k < 100; ++k) clock.AddPulse(train_after.Pulse(k));
  const PpsEstimate estimate = clock.Estimate(train_after.Pulse(99));
  EXPECT_EQ(estimate.counters.restarts, 1u);
  EXPECT_EQ(estimate.counters.spurious, 2u);
  EXPECT_EQ(estimate.status, PpsStatus::kLocked);
  const Errors errors = Check(clock, after, 99);
  EXPECT_LT(std::abs(errors.offset_ns), kOffsetBoundNs);
  EXPECT_LT(std::abs(errors.drift_ppm), kDriftBoundPpm);
}

}  // namespace
}  // namespace flat2d::hal::gpio
