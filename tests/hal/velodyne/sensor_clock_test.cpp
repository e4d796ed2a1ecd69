#include "hal/velodyne/sensor_clock.hpp"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::hal::velodyne {
namespace {

constexpr TimeNs kMinute = 60 * kNsPerSecond;
// 2016-01-21T08:18:02Z (the MRPT VLP-16 capture) and the top of its hour.
constexpr TimeNs kFixTime = 1'453'364'282 * kNsPerSecond;
constexpr TimeNs kHour8 = kFixTime - (18 * 60 + 2) * kNsPerSecond;

// What a UTC-synchronised sensor stamps at absolute time t (t >= 0).
std::uint32_t UsPastHour(TimeNs t) {
  return static_cast<std::uint32_t>(t % kNsPerHour / kNsPerUs);
}

PositionPacket FixPacket(std::uint32_t us_past_hour, TimeNs fix_utc_ns, char status = 'A') {
  PositionPacket packet;
  packet.us_past_hour = us_past_hour;
  packet.pps_status = PpsStatus::kLocked;
  RmcFix fix;
  fix.utc_time_ns = fix_utc_ns;
  fix.has_time = true;
  fix.status = status;
  fix.valid = status == 'A';
  packet.rmc = fix;
  return packet;
}

TEST(ResolveHourRelative, SameHour) {
  EXPECT_EQ(ResolveHourRelative(10 * 60'000'000u, kHour8 + 30 * kMinute), kHour8 + 10 * kMinute);
}

TEST(ResolveHourRelative, ReferenceJustBeforeTheHourPicksTheNextHour) {
  const TimeNs reference = kHour8 + kNsPerHour - 100 * kNsPerMs;  // 08:59:59.900
  EXPECT_EQ(ResolveHourRelative(100'000u, reference), kHour8 + kNsPerHour + 100 * kNsPerMs);
}

TEST(ResolveHourRelative, ReferenceJustAfterTheHourPicksThePreviousHour) {
  const TimeNs reference = kHour8 + kNsPerHour + 100 * kNsPerMs;  // 09:00:00.100
  EXPECT_EQ(ResolveHourRelative(3'599'900'000u, reference), kHour8 + kNsPerHour - 100 * kNsPerMs);
}

TEST(ResolveHourRelative, HalfHourTieGoesToTheLaterTime) {
  EXPECT_EQ(ResolveHourRelative(0u, kHour8 + 30 * kMinute), kHour8 + kNsPerHour);
  EXPECT_EQ(ResolveHourRelative(1'800'000'000u, kHour8), kHour8 + 30 * kMinute);
}

TEST(ResolveHourRelative, ReferencesBeforeTheEpochAndOverlongTimestamps) {
  EXPECT_EQ(ResolveHourRelative(3'599'500'000u, -kNsPerSecond), -500 * kNsPerMs);
  EXPECT_EQ(ResolveHourRelative(0u, -kNsPerSecond), 0);
  // 3,600,000,005 us is not a valid timestamp; it is taken modulo the hour.
  EXPECT_EQ(ResolveHourRelative(3'600'000'005u, kHour8), kHour8 + 5 * kNsPerUs);
}

TEST(ResolveHourRelative, RecoversRandomTimesFromReferencesWithinHalfAnHour) {
  constexpr unsigned kSeed = 42;
  std::mt19937_64 random(kSeed);
  // Uniform over 2000-01-01 .. 2040-01-01, whole microseconds.
  std::uniform_int_distribution<TimeNs> time_us(946'684'800'000'000, 2'208'988'800'000'000);
  std::uniform_int_distribution<TimeNs> offset(-kNsPerHour / 2 + 1, kNsPerHour / 2 - 1);
  for (int trial = 0; trial < 10'000; ++trial) {
    const TimeNs truth = time_us(random) * kNsPerUs;
    const TimeNs reference = truth + offset(random);
    ASSERT_EQ(ResolveHourRelative(UsPastHour(truth), reference), truth)
        << "seed " << kSeed << " trial " << trial << " reference " << reference;
  }
}

TEST(SensorClock, SensorOnlyStartsInHourZeroAndUnwrapsByContinuity) {
  SensorClock clock;
  EXPECT_EQ(clock.Resolve(3'599'000'000u, 0), 3'599 * kNsPerSecond);
  EXPECT_EQ(clock.Resolve(3'599'900'000u, 0), 3'599'900 * kNsPerMs);
  EXPECT_EQ(clock.Resolve(100'000u, 0), 3'600'100 * kNsPerMs);  // wrapped into hour 1
  // Steps of 25 minutes keep unwrapping through several hours.
  TimeNs expected = 3'600'100 * kNsPerMs;
  for (int step = 0; step < 10; ++step) {
    expected += 25 * kMinute;
    EXPECT_EQ(clock.Resolve(UsPastHour(expected), 0), expected) << "step " << step;
  }
  EXPECT_EQ(clock.source(), TimeSource::kSensorOnly);
  EXPECT_EQ(TimeSourceName(clock.source()), "sensor-only");
}

TEST(SensorClock, HostTimePicksTheHourAndSensorKeepsTheSubHourTime) {
  SensorClock clock;
  // Synchronised sensor; host times 0-3 ms late (capture latency), steps of 7 minutes.
  for (int k = 0; k < 20; ++k) {
    const TimeNs truth = kHour8 + 50 * kMinute + k * 7 * kMinute + 123 * kNsPerUs;
    const TimeNs host = truth + (k % 4) * kNsPerMs;
    EXPECT_EQ(clock.Resolve(UsPastHour(truth), host), truth) << "packet " << k;
  }
  EXPECT_EQ(clock.source(), TimeSource::kHost);
  EXPECT_EQ(clock.stats().host_times_rejected, 0u);
}

TEST(SensorClock, UnsyncedSensorNearHalfAnHourFromHostDoesNotFlipHours) {
  // The sensor runs 29 min 59.95 s ahead of the host; host jitter of +-0.2 s alone would
  // put the nearest hour on either side. The established offset keeps the choice stable.
  constexpr TimeNs kSensorAhead = 30 * kMinute - 50 * kNsPerMs;
  std::mt19937 random(7);
  std::uniform_int_distribution<TimeNs> jitter(-200 * kNsPerMs, 200 * kNsPerMs);
  SensorClock clock;
  const TimeNs first = clock.Resolve(UsPastHour(kHour8 + kSensorAhead), kHour8);
  int naive_flips = 0;
  for (int k = 1; k < 500; ++k) {
    const TimeNs host = kHour8 + k * 10 * kNsPerMs;
    const std::uint32_t us = UsPastHour(host + kSensorAhead);
    const TimeNs noisy_host = host + jitter(random);
    naive_flips += ResolveHourRelative(us, noisy_host) - noisy_host < 0 ? 1 : 0;
    ASSERT_EQ(clock.Resolve(us, noisy_host) - first, k * 10 * kNsPerMs) << "packet " << k;
  }
  EXPECT_GT(naive_flips, 0) << "the test should include host times that alone pick another hour";
  EXPECT_EQ(clock.stats().host_times_rejected, 0u);
}

TEST(SensorClock, SingleHostGlitchIsRejectedAndCounted) {
  SensorClock clock;
  for (int k = 0; k < 10; ++k) {
    const TimeNs truth = kHour8 + 55 * kMinute + k * kMinute;
    // Packet 4 carries a host time 3 h 10 min 7 s off (not whole hours: see below).
    const TimeNs glitch = 3 * kNsPerHour + 10 * kMinute + 7 * kNsPerSecond;
    const TimeNs host = k == 4 ? truth + glitch : truth;
    EXPECT_EQ(clock.Resolve(UsPastHour(truth), host), truth) << "packet " << k;
  }
  EXPECT_EQ(clock.stats().host_times_rejected, 1u);
  EXPECT_EQ(clock.stats().host_reanchors, 0u);
}

TEST(SensorClock, ConfirmedHostStepReanchorsTheHour) {
  SensorClock clock;
  // From packet 5 on the host clock is 2 h 13 min ahead (someone set it by hand).
  std::vector<TimeNs> resolved;
  for (int k = 0; k < 10; ++k) {
    const TimeNs truth = kHour8 + k * kMinute;
    const TimeNs host = k >= 5 ? truth + 2 * kNsPerHour + 13 * kMinute : truth;
    resolved.push_back(clock.Resolve(UsPastHour(truth), host));
  }
  EXPECT_EQ(resolved[4], kHour8 + 4 * kMinute);
  EXPECT_EQ(resolved[5], kHour8 + 5 * kMinute);  // first disagreement: continuity
  // Confirmed: the host picks the hour again, the nearest to it (the sensor keeps 08:06).
  EXPECT_EQ(resolved[6], kHour8 + 6 * kMinute + 2 * kNsPerHour);
  EXPECT_EQ(resolved[9], kHour8 + 9 * kMinute + 2 * kNsPerHour);
  EXPECT_EQ(clock.stats().host_times_rejected, 1u);
  EXPECT_EQ(clock.stats().host_reanchors, 1u);
}

TEST(SensorClock, WholeHourHostJumpLeavesNoTraceAndIsFollowed) {
  SensorClock clock;
  const TimeNs truth = kHour8 + 10 * kMinute;
  EXPECT_EQ(clock.Resolve(UsPastHour(truth), truth), truth);
  EXPECT_EQ(clock.Resolve(UsPastHour(truth + kMinute), truth + kMinute + kNsPerHour),
            truth + kMinute + kNsPerHour);
  EXPECT_EQ(clock.stats().host_times_rejected, 0u);
}

TEST(SensorClock, GpsFixAnchorsTheHourWithoutHostTimes) {
  SensorClock clock;
  clock.ObservePositionPacket(FixPacket(UsPastHour(kFixTime + 342 * kNsPerMs), kFixTime));
  EXPECT_EQ(clock.source(), TimeSource::kGps);
  EXPECT_EQ(clock.stats().gps_fixes_accepted, 1u);
  // Data packets every 9 minutes from 08:18:02.4, across 09:00 and 10:00.
  for (int k = 0; k < 12; ++k) {
    const TimeNs truth = kFixTime + 400 * kNsPerMs + k * 9 * kMinute;
    EXPECT_EQ(clock.Resolve(UsPastHour(truth), 0), truth) << "packet " << k;
  }
}

TEST(SensorClock, GpsWinsOverAWrongHostClock) {
  SensorClock clock;
  // Host clock one day and 17 minutes fast, consistently; later it jumps back an hour.
  constexpr TimeNs kHostError = 24 * kNsPerHour + 17 * kMinute;
  // Alone, the host clock picks the hour nearest to it: the right time of day, a day late.
  EXPECT_EQ(clock.Resolve(UsPastHour(kFixTime), kFixTime + kHostError),
            kFixTime + 24 * kNsPerHour);
  EXPECT_EQ(clock.source(), TimeSource::kHost);
  clock.ObservePositionPacket(FixPacket(UsPastHour(kFixTime + 500 * kNsPerMs), kFixTime));
  EXPECT_EQ(clock.source(), TimeSource::kGps);
  for (int k = 1; k < 30; ++k) {
    const TimeNs truth = kFixTime + k * 3 * kMinute;
    const TimeNs host = truth + kHostError - (k >= 20 ? kNsPerHour : 0);
    EXPECT_EQ(clock.Resolve(UsPastHour(truth), host), truth) << "packet " << k;
  }
  // Under GPS the host clock is not consulted, so its jump is neither followed nor counted.
  EXPECT_EQ(clock.stats().host_times_rejected, 0u);
  EXPECT_EQ(clock.stats().host_reanchors, 0u);
}

TEST(SensorClock, VoidStaleOrTimelessFixesAreRejected) {
  SensorClock clock;
  clock.ObservePositionPacket(FixPacket(UsPastHour(kFixTime), kFixTime, 'V'));
  // The sensor says 08:20:02: the fix is two minutes old, so the sensor does not follow it.
  clock.ObservePositionPacket(FixPacket(UsPastHour(kFixTime + 2 * kMinute), kFixTime));
  PositionPacket timeless = FixPacket(UsPastHour(kFixTime), kFixTime);
  timeless.rmc->has_time = false;
  clock.ObservePositionPacket(timeless);
  PositionPacket no_gps;  // no NMEA sentence at all: ignored, not counted
  clock.ObservePositionPacket(no_gps);
  EXPECT_EQ(clock.stats().gps_fixes_rejected, 3u);
  EXPECT_EQ(clock.stats().gps_fixes_accepted, 0u);
  EXPECT_EQ(clock.source(), TimeSource::kSensorOnly);
  // Agreement within the tolerance (2.9 s) is accepted.
  clock.ObservePositionPacket(FixPacket(UsPastHour(kFixTime + 2'900 * kNsPerMs), kFixTime));
  EXPECT_EQ(clock.source(), TimeSource::kGps);
}

TEST(SensorClock, GpsFixJustBeforeTheHourWithPacketJustAfter) {
  SensorClock clock;
  // Fix 08:59:59, packet assembled at 09:00:00.300: the hour comes from the packet side.
  const TimeNs fix = kHour8 + kNsPerHour - kNsPerSecond;
  clock.ObservePositionPacket(FixPacket(300'000u, fix));
  ASSERT_EQ(clock.source(), TimeSource::kGps);
  EXPECT_EQ(clock.Resolve(400'000u, 0), kHour8 + kNsPerHour + 400 * kNsPerMs);
}

}  // namespace
}  // namespace flat2d::hal::velodyne
