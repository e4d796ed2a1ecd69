#include "hal/gpio/pps_input.hpp"

#include <gtest/gtest.h>

#include <cstdint>

#include "tests/hal/gpio/fake_lines.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::gpio {
namespace {

using testing::FakeEdgeSource;

constexpr TimeNs kFirstPulseNs = 1'700'000'000 * kNsPerSecond + 250'000;  // 250 us late

PpsClock MakeClock() {
  Result<PpsClock> clock = PpsClock::Create({});
  EXPECT_TRUE(clock.ok());
  return std::move(clock).value();
}

// A 100 ms pulse every second, both edges, as a line requested for both edges reports it.
void QueuePulses(FakeEdgeSource& source, int first, int count) {
  for (int k = first; k < first + count; ++k) {
    const TimeNs rise = kFirstPulseNs + k * kNsPerSecond;
    source.Queue(rise, Edge::kRising);
    source.Queue(rise + 100 * kNsPerMs, Edge::kFalling);
  }
}

TEST(PpsInputTest, FeedsRisingEdgesToTheClock) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  QueuePulses(source, 0, 10);
  Result<PpsPollResult> polled = input.Poll(kNsPerSecond);
  ASSERT_TRUE(polled.ok()) << polled.error().message;
  EXPECT_EQ(polled->events, 20u);
  EXPECT_EQ(polled->pulses, 10u);
  EXPECT_EQ(polled->spurious, 0u);
  EXPECT_EQ(polled->dropped_events, 0u);
  EXPECT_EQ(source.reads(), 2u) << "16 events, then the remaining 4";
  const PpsEstimate estimate = clock.Estimate(kFirstPulseNs + 9 * kNsPerSecond);
  EXPECT_EQ(estimate.status, PpsStatus::kLocked);
  EXPECT_EQ(estimate.offset_ns, 250'000);
  EXPECT_EQ(estimate.counters.accepted, 10u);
}

TEST(PpsInputTest, FallingEdgePulsesForAnInvertedReceiver) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock, Edge::kFalling);
  QueuePulses(source, 0, 5);
  Result<PpsPollResult> polled = input.Poll(kNsPerSecond);
  ASSERT_TRUE(polled.ok());
  EXPECT_EQ(polled->pulses, 5u);
  EXPECT_EQ(clock.Estimate(kFirstPulseNs + 4 * kNsPerSecond).offset_ns, 100'250'000);
}

TEST(PpsInputTest, TimeoutReturnsNothing) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  Result<PpsPollResult> polled = input.Poll(200 * kNsPerMs);
  ASSERT_TRUE(polled.ok());
  EXPECT_EQ(polled->events, 0u);
  EXPECT_EQ(source.waited_ns(), 200 * kNsPerMs);
  EXPECT_EQ(clock.Estimate(0).status, PpsStatus::kNoPps);
}

TEST(PpsInputTest, CountsSequenceGapsAsDroppedEvents) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  source.Queue({kFirstPulseNs, Edge::kRising, 0});
  source.Queue({kFirstPulseNs + kNsPerSecond, Edge::kRising, 1});
  // Sequence 2 and 3 (the third pulse and a falling edge) never arrive.
  source.Queue({kFirstPulseNs + 3 * kNsPerSecond, Edge::kRising, 4});
  Result<PpsPollResult> polled = input.Poll(kNsPerSecond);
  ASSERT_TRUE(polled.ok());
  EXPECT_EQ(polled->dropped_events, 2u);
  EXPECT_EQ(clock.Estimate(kFirstPulseNs + 3 * kNsPerSecond).counters.missed, 1u);
}

TEST(PpsInputTest, CountsPulsesTheClockRejects) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  QueuePulses(source, 0, 3);
  source.Queue(kFirstPulseNs + 2 * kNsPerSecond + 400 * kNsPerMs, Edge::kRising);
  Result<PpsPollResult> polled = input.Poll(kNsPerSecond);
  ASSERT_TRUE(polled.ok());
  EXPECT_EQ(polled->pulses, 4u);
  EXPECT_EQ(polled->spurious, 1u);
}

TEST(PpsInputTest, PropagatesSourceErrors) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  QueuePulses(source, 0, 1);
  source.FailNextRead("reading events from line 3 on gpiochip0: Input/output error");
  Result<PpsPollResult> polled = input.Poll(kNsPerSecond);
  ASSERT_FALSE(polled.ok());
  EXPECT_EQ(polled.error().message, "reading events from line 3 on gpiochip0: Input/output error");
}

TEST(PpsInputTest, PollAllocatesNothing) {
  FakeEdgeSource source;
  PpsClock clock = MakeClock();
  PpsInput input(source, clock);
  QueuePulses(source, 0, 1000);
  const std::uint64_t before = flat2d::testing::AllocationCount();
  std::size_t pulses = 0;
  for (int i = 0; i < 200; ++i) {
    Result<PpsPollResult> polled = input.Poll(0);
    if (polled.ok()) pulses += polled->pulses;
  }
  EXPECT_EQ(flat2d::testing::AllocationCount() - before, 0u);
  EXPECT_EQ(pulses, 1000u);
}

}  // namespace
}  // namespace flat2d::hal::gpio
