// CanReplaySource schedules against a fake clock: speeds 1 and 2, as fast as possible,
// log times that go backwards, and a whole real log.
#include "hal/can/can_replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "hal/can/candump_log.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::can {
namespace {

constexpr TimeNs kClockStartNs = 7'000'000'000;
constexpr TimeNs kLogStartNs = 1'674'148'739'212'264'000;

// Time advances only when the replay sleeps, so the sleeps are the schedule.
class FakeClock final : public net::ReplayClock {
 public:
  TimeNs Now() override { return now_ns_; }
  void SleepUntil(TimeNs deadline_ns) override {
    EXPECT_GT(deadline_ns, now_ns_) << "slept backwards or for nothing";
    sleeps_.push_back(deadline_ns - kClockStartNs);
    now_ns_ = std::max(now_ns_, deadline_ns);
  }
  void Advance(TimeNs ns) { now_ns_ += ns; }
  TimeNs elapsed() const { return now_ns_ - kClockStartNs; }
  const std::vector<TimeNs>& sleeps() const { return sleeps_; }  // offsets from the start

 private:
  TimeNs now_ns_ = kClockStartNs;
  std::vector<TimeNs> sleeps_;
};

class VectorSource final : public CanFrameSource {
 public:
  explicit VectorSource(const std::vector<TimeNs>& offsets_ns) {
    for (std::size_t i = 0; i < offsets_ns.size(); ++i) {
      CanFrame frame;
      frame.time_ns = kLogStartNs + offsets_ns[i];
      frame.id = static_cast<std::uint32_t>(i);
      frames_.push_back(frame);
    }
  }
  bool Next(CanFrame& frame) override {
    if (next_ >= frames_.size()) return false;
    frame = frames_[next_++];
    return true;
  }

 private:
  std::vector<CanFrame> frames_;
  std::size_t next_ = 0;
};

// Replays and records, per frame, the fake clock's offset when the frame was released.
std::vector<TimeNs> ReleaseTimes(CanReplaySource& replay, FakeClock& clock) {
  std::vector<TimeNs> times;
  CanFrame frame;
  while (replay.Next(frame)) {
    EXPECT_EQ(frame.id, times.size()) << "frames reordered";
    times.push_back(clock.elapsed());
  }
  return times;
}

const std::vector<TimeNs> kOffsets = {0, 10'000'000, 10'000'000, 25'000'000, 1'000'000'000};

TEST(CanReplay, SpeedOneKeepsTheLogTiming) {
  VectorSource source(kOffsets);
  FakeClock clock;
  CanReplaySource replay(source, clock, {.speed = 1.0});
  EXPECT_EQ(ReleaseTimes(replay, clock), kOffsets);
  // Equal times share one sleep; the first frame needs none.
  EXPECT_EQ(clock.sleeps(), (std::vector<TimeNs>{10'000'000, 25'000'000, 1'000'000'000}));
  EXPECT_EQ(replay.stats().frames, 5u);
  EXPECT_EQ(replay.stats().sleeps, 3u);
  EXPECT_EQ(replay.stats().non_monotonic, 0u);
}

TEST(CanReplay, SpeedTwoHalvesEveryOffset) {
  VectorSource source(kOffsets);
  FakeClock clock;
  CanReplaySource replay(source, clock, {.speed = 2.0});
  EXPECT_EQ(ReleaseTimes(replay, clock),
            (std::vector<TimeNs>{0, 5'000'000, 5'000'000, 12'500'000, 500'000'000}));
}

TEST(CanReplay, AsFastAsPossibleNeverSleeps) {
  for (const double speed : {0.0, -1.0}) {
    VectorSource source(kOffsets);
    FakeClock clock;
    CanReplaySource replay(source, clock, {.speed = speed});
    EXPECT_EQ(ReleaseTimes(replay, clock), std::vector<TimeNs>(kOffsets.size(), 0));
    EXPECT_TRUE(clock.sleeps().empty());
    EXPECT_EQ(replay.stats().frames, kOffsets.size());
  }
}

// A slow consumer makes frames late; the ones after are not pushed back.
TEST(CanReplay, LatenessDoesNotAccumulate) {
  VectorSource source({0, 10'000'000, 20'000'000, 30'000'000});
  FakeClock clock;
  CanReplaySource replay(source, clock);
  CanFrame frame;
  ASSERT_TRUE(replay.Next(frame));
  clock.Advance(25'000'000);  // the consumer stalls past frames 1 and 2
  ASSERT_TRUE(replay.Next(frame));
  ASSERT_TRUE(replay.Next(frame));
  EXPECT_EQ(clock.elapsed(), 25'000'000);
  ASSERT_TRUE(replay.Next(frame));
  EXPECT_EQ(clock.elapsed(), 30'000'000);
}

TEST(CanReplay, SmallBackwardStepsAreReleasedAtOnceAndCounted) {
  VectorSource source({0, 20'000'000, 15'000'000, 30'000'000});
  FakeClock clock;
  CanReplaySource replay(source, clock);
  EXPECT_EQ(ReleaseTimes(replay, clock),
            (std::vector<TimeNs>{0, 20'000'000, 20'000'000, 30'000'000}));
  EXPECT_EQ(replay.stats().non_monotonic, 1u);
  EXPECT_EQ(replay.stats().rebased, 0u);
  EXPECT_EQ(replay.stats().largest_backward_step_ns, 5'000'000);
}

// A log restarted 100 s earlier: the frames after the jump keep their own spacing.
TEST(CanReplay, LargeBackwardJumpsMoveTheOrigin) {
  VectorSource source({100'000'000'000, 100'010'000'000, 0, 10'000'000, 30'000'000});
  FakeClock clock;
  CanReplaySource replay(source, clock);
  EXPECT_EQ(ReleaseTimes(replay, clock),
            (std::vector<TimeNs>{0, 10'000'000, 10'000'000, 20'000'000, 40'000'000}));
  EXPECT_EQ(replay.stats().non_monotonic, 1u);
  EXPECT_EQ(replay.stats().rebased, 1u);
  EXPECT_EQ(replay.stats().largest_backward_step_ns, 100'010'000'000);
}

TEST(CanReplay, RealLogAtSpeedOneTwoAndUnpaced) {
  FLAT2D_REQUIRE_DATA(path, "can/eldominio_candump/civic_19_type_r__turnonanddrive.log");
  constexpr TimeNs kLogDurationNs = 65'481'943'000;
  for (const double speed : {1.0, 2.0, 0.0}) {
    Result<CandumpReader> reader = CandumpReader::Open(path);
    ASSERT_TRUE(reader.ok());
    FakeClock clock;
    CanReplaySource replay(*reader, clock, {.speed = speed});
    CanFrame frame;
    TimeNs first_log_ns = -1;
    while (replay.Next(frame)) {
      if (first_log_ns < 0) first_log_ns = frame.time_ns;
      // Every frame is released exactly at its scaled log offset (the clock never lags).
      if (speed > 0) {
        const double due_ns = static_cast<double>(frame.time_ns - first_log_ns) / speed;
        ASSERT_EQ(clock.elapsed(), static_cast<TimeNs>(due_ns + 0.5)) << "speed " << speed;
      }
    }
    EXPECT_EQ(replay.stats().frames, 28835u);
    EXPECT_EQ(replay.stats().non_monotonic, 0u);
    const TimeNs expected_ns = speed > 0 ? static_cast<TimeNs>(kLogDurationNs / speed) : 0;
    EXPECT_EQ(clock.elapsed(), expected_ns) << "speed " << speed;
  }
}

}  // namespace
}  // namespace flat2d::hal::can
