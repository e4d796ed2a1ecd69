#include "hal/gpio/pose_valid_output.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "tests/hal/gpio/fake_lines.hpp"

namespace flat2d::hal::gpio {
namespace {

using testing::FakeOutput;

constexpr TimeNs kStart = 1'000 * kNsPerSecond;  // a CLOCK_MONOTONIC reading after boot

PoseValidOptions Options(std::int64_t min_on_ms, std::int64_t min_off_ms,
                         ActiveLevel level = ActiveLevel::kHigh) {
  return {.min_on_ms = min_on_ms, .min_off_ms = min_off_ms, .active_level = level};
}

PoseValidOutput MakeOutput(FakeOutput& line, const PoseValidOptions& options) {
  Result<PoseValidOutput> output = PoseValidOutput::Create(line, options);
  EXPECT_TRUE(output.ok()) << output.error().message;
  return std::move(output).value();
}

// Feeds `valid` every 10 ms over [from, to) and returns the first time the line turned on.
std::optional<TimeNs> HoldPose(PoseValidOutput& output, bool valid, TimeNs from, TimeNs to) {
  std::optional<TimeNs> turned_on;
  for (TimeNs t = from; t < to; t += 10 * kNsPerMs) {
    const bool was_on = output.on();
    EXPECT_TRUE(output.Update(valid, t).ok());
    if (!was_on && output.on() && !turned_on) turned_on = t;
  }
  return turned_on;
}

TEST(PoseValidOutputTest, CreateDrivesTheSafeValue) {
  FakeOutput high_line(true);
  PoseValidOutput high = MakeOutput(high_line, Options(200, 1000));
  EXPECT_EQ(high_line.writes(), std::vector<bool>{false});
  EXPECT_FALSE(high.on());

  FakeOutput low_line(false);
  PoseValidOutput low = MakeOutput(low_line, Options(200, 1000, ActiveLevel::kLow));
  EXPECT_EQ(low_line.writes(), std::vector<bool>{true});
  EXPECT_TRUE(PoseValidSafeValue(Options(0, 0, ActiveLevel::kLow)));
  EXPECT_FALSE(PoseValidSafeValue(Options(0, 0, ActiveLevel::kHigh)));
}

TEST(PoseValidOutputTest, TurnsOnOnlyAfterThePoseHeldValidForMinOn) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(200, 1000));
  const std::optional<TimeNs> on = HoldPose(output, true, kStart, kStart + kNsPerSecond);
  ASSERT_TRUE(on.has_value());
  EXPECT_EQ(*on - kStart, 200 * kNsPerMs);
  EXPECT_TRUE(line.value());
  EXPECT_EQ(output.switches(), 1u);
}

TEST(PoseValidOutputTest, InvalidPoseTurnsTheLineOffAtOnce) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(200, 1000));
  HoldPose(output, true, kStart, kStart + kNsPerSecond);
  ASSERT_TRUE(output.on());
  ASSERT_TRUE(output.Update(false, kStart + kNsPerSecond).ok());
  EXPECT_FALSE(output.on());
  EXPECT_FALSE(line.value());
}

TEST(PoseValidOutputTest, StaysOffForMinOffAfterTurningOff) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(200, 1000));
  HoldPose(output, true, kStart, kStart + kNsPerSecond);
  const TimeNs off_at = kStart + kNsPerSecond;
  ASSERT_TRUE(output.Update(false, off_at).ok());
  // Valid again right away: min_on is met after 200 ms, but min_off holds until 1000 ms.
  const std::optional<TimeNs> on =
      HoldPose(output, true, off_at + 10 * kNsPerMs, off_at + 3 * kNsPerSecond);
  ASSERT_TRUE(on.has_value());
  EXPECT_EQ(*on - off_at, 1000 * kNsPerMs);
  EXPECT_EQ(output.switches(), 3u);
}

TEST(PoseValidOutputTest, FlickeringPoseNeverTurnsTheLineOn) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(200, 1000));
  for (TimeNs t = kStart; t < kStart + 10 * kNsPerSecond; t += 10 * kNsPerMs) {
    const bool valid = ((t - kStart) / (50 * kNsPerMs)) % 2 == 0;  // 50 ms on, 50 ms off
    ASSERT_TRUE(output.Update(valid, t).ok());
    ASSERT_FALSE(output.on()) << "at " << (t - kStart) / kNsPerMs << " ms";
  }
  EXPECT_EQ(output.switches(), 0u);
}

TEST(PoseValidOutputTest, RandomStatesSwitchAtMostOncePerHoldPeriod) {
  const std::uint32_t seed = 4242;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::bernoulli_distribution flip(0.02);  // a state change every 0.5 s on average
  FakeOutput line;
  const PoseValidOptions options = Options(200, 1000);
  PoseValidOutput output = MakeOutput(line, options);
  bool valid = false;
  std::optional<TimeNs> last_on;
  std::optional<TimeNs> last_off;
  for (TimeNs t = kStart; t < kStart + 600 * kNsPerSecond; t += 10 * kNsPerMs) {
    if (flip(rng)) valid = !valid;
    const bool was_on = output.on();
    ASSERT_TRUE(output.Update(valid, t).ok());
    if (!valid) {
      ASSERT_FALSE(output.on()) << "an invalid pose never leaves the line on";
    }
    if (!was_on && output.on()) {
      if (last_off) {
        ASSERT_GE(t - *last_off, options.min_off_ms * kNsPerMs);
      }
      last_on = t;
    }
    if (was_on && !output.on()) last_off = t;
  }
  // Turn-ons are at least min_off apart, and each is followed by at most one turn-off.
  const std::uint64_t bound = 2 * (600'000 / options.min_off_ms + 1);
  std::printf("%llu switches in 600 s (bound %llu)\n",
              static_cast<unsigned long long>(output.switches()),
              static_cast<unsigned long long>(bound));
  EXPECT_GT(output.switches(), 10u) << "the test should exercise switching";
  EXPECT_LE(output.switches(), bound);
  EXPECT_TRUE(last_on.has_value());
}

TEST(PoseValidOutputTest, ActiveLowInvertsTheLine) {
  FakeOutput line(true);
  PoseValidOutput output = MakeOutput(line, Options(0, 0, ActiveLevel::kLow));
  ASSERT_TRUE(output.Update(true, kStart).ok());
  EXPECT_TRUE(output.on());
  EXPECT_FALSE(line.value());
  ASSERT_TRUE(output.Update(false, kStart + kNsPerMs).ok());
  EXPECT_TRUE(line.value());
}

TEST(PoseValidOutputTest, StopForcesOffAndIgnoresLaterUpdates) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(0, 0));
  ASSERT_TRUE(output.Update(true, kStart).ok());
  ASSERT_TRUE(line.value());
  ASSERT_TRUE(output.Stop().ok());
  EXPECT_FALSE(line.value());
  EXPECT_TRUE(output.stopped());
  ASSERT_TRUE(output.Update(true, kStart + kNsPerSecond).ok());
  EXPECT_FALSE(line.value());
}

TEST(PoseValidOutputTest, DestructionDrivesTheSafeValueOnce) {
  FakeOutput line;
  {
    PoseValidOutput output = MakeOutput(line, Options(0, 0, ActiveLevel::kLow));
    ASSERT_TRUE(output.Update(true, kStart).ok());
    ASSERT_FALSE(line.value());
    PoseValidOutput moved(std::move(output));  // the moved-from output must not write
    EXPECT_TRUE(moved.on());
  }
  EXPECT_TRUE(line.value());
  EXPECT_EQ(line.writes(), (std::vector<bool>{true, false, true}));
}

TEST(PoseValidOutputTest, FailedTurnOffIsReportedAndRetried) {
  FakeOutput line;
  PoseValidOutput output = MakeOutput(line, Options(0, 0));
  ASSERT_TRUE(output.Update(true, kStart).ok());
  line.FailNextWrites(1);
  const Status failed = output.Update(false, kStart + kNsPerMs);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().message, "fake write failure");
  EXPECT_TRUE(output.on()) << "the line still shows valid as far as we know";
  EXPECT_EQ(output.write_failures(), 1u);
  ASSERT_TRUE(output.Update(false, kStart + 2 * kNsPerMs).ok());
  EXPECT_FALSE(output.on());
  EXPECT_FALSE(line.value());
}

TEST(PoseValidOutputTest, CreateFailsOnBadOptionsOrAnUnwritableLine) {
  FakeOutput line;
  Result<PoseValidOutput> bad = PoseValidOutput::Create(line, Options(-1, 0));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "pose_valid.min_on_ms must be >= 0, got -1");
  EXPECT_FALSE(PoseValidOutput::Create(line, Options(0, -5)).ok());
  line.FailNextWrites(1);
  EXPECT_FALSE(PoseValidOutput::Create(line, Options(0, 0)).ok());
}

}  // namespace
}  // namespace flat2d::hal::gpio
