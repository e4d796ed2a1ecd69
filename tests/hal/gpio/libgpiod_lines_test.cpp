#include "hal/gpio/libgpiod_lines.hpp"

#include <gtest/gtest.h>

#include <array>
#include <ctime>
#include <filesystem>
#include <memory>
#include <vector>

#include "tests/hal/gpio/gpio_sim.hpp"

namespace flat2d::hal::gpio {
namespace {

using testing::SimulatedChip;

// Opening a missing or wrong chip works without GPIO hardware.

EdgeInputOptions InputOn(const std::string& chip, unsigned offset) {
  EdgeInputOptions options;
  options.line.chip = chip;
  options.line.offset = offset;
  return options;
}

TEST(LibgpiodLinesTest, MissingChipByNameNamesTheChip) {
  auto input = LibgpiodEdgeInput::Open(InputOn("flat2d-no-such-chip", 17));
  ASSERT_FALSE(input.ok());
  EXPECT_EQ(input.error().message, "flat2d-no-such-chip: No such file or directory");
  if (!std::filesystem::exists("/dev/gpiochip0")) {
    EXPECT_EQ(LibgpiodEdgeInput::Open(InputOn("gpiochip0", 17)).error().message,
              "gpiochip0: No such file or directory");
  }
}

TEST(LibgpiodLinesTest, MissingChipByPathOrNumberNamesTheChip) {
  EXPECT_EQ(LibgpiodEdgeInput::Open(InputOn("/dev/gpiochip-flat2d-missing", 0)).error().message,
            "/dev/gpiochip-flat2d-missing: No such file or directory");
  OutputOptions output;
  output.line.chip = "4242";
  EXPECT_EQ(LibgpiodOutput::Open(output).error().message,
            "gpiochip4242: No such file or directory");
}

TEST(LibgpiodLinesTest, AFileThatIsNotAGpioChipIsSaidToBeSo) {
  EXPECT_EQ(LibgpiodEdgeInput::Open(InputOn("/dev/null", 0)).error().message,
            "/dev/null: not a GPIO chip character device");
}

TEST(LibgpiodLinesTest, EmptyChipIsAConfigurationError) {
  EXPECT_EQ(LibgpiodEdgeInput::Open(InputOn("", 0)).error().message,
            "GPIO chip not configured (empty chip name)");
}

TEST(LibgpiodLinesTest, EventClockFollowsTheKernelVersion) {
  EXPECT_EQ(V1EventClockForKernel("6.1.0-18-amd64"), EventClock::kMonotonic);
  EXPECT_EQ(V1EventClockForKernel("5.7.0"), EventClock::kMonotonic);
  EXPECT_EQ(V1EventClockForKernel("5.10.120-ti-r47"), EventClock::kMonotonic);
  EXPECT_EQ(V1EventClockForKernel("5.6.19"), EventClock::kRealtime);
  EXPECT_EQ(V1EventClockForKernel("4.19.0-21-armmp"), EventClock::kRealtime);
  EXPECT_EQ(V1EventClockForKernel("garbage"), EventClock::kMonotonic);
  EXPECT_EQ(V1EventClockForKernel(""), EventClock::kMonotonic);
}

// Against a simulated chip, where one exists.

constexpr unsigned kNumLines = 8;
constexpr unsigned kNamedOffset = 3;
const char* const kLineName = "flat2d-pps";

TimeNs RealtimeNow() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
}

// gpio-sim raises its interrupts from irq_work, so edges arrive shortly after the pull.
std::vector<EdgeEvent> ReadUntil(LibgpiodEdgeInput& input, std::size_t count,
                                 std::vector<EdgeEvent> events = {}) {
  std::array<EdgeEvent, kMaxEventsPerRead> buffer{};
  for (int attempt = 0; attempt < 20 && events.size() < count; ++attempt) {
    Result<bool> ready = input.Wait(100 * kNsPerMs);
    if (!ready.ok() || !*ready) continue;
    Result<std::size_t> read = input.Read(buffer);
    if (!read.ok()) break;
    events.insert(events.end(), buffer.begin(), buffer.begin() + static_cast<long>(*read));
  }
  return events;
}

class LibgpiodSimTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto chip = SimulatedChip::Create(kNumLines, kNamedOffset, kLineName);
    if (!chip.ok()) GTEST_SKIP() << chip.error().message;
    sim_ = std::move(chip).value();
    std::printf("using %s chip %s\n", sim_->kind().c_str(), sim_->chip_name().c_str());
  }

  LineAddress Line(unsigned offset) const { return {sim_->chip_name(), offset, ""}; }

  std::unique_ptr<SimulatedChip> sim_;
};

TEST_F(LibgpiodSimTest, RisingEdgesCarryRealtimeKernelStamps) {
  auto input = LibgpiodEdgeInput::Open({.line = Line(1)});
  ASSERT_TRUE(input.ok()) << input.error().message;
  const TimeNs before = RealtimeNow();
  ASSERT_TRUE(sim_->Pull(1, true).ok());
  std::vector<EdgeEvent> events = ReadUntil(*input, 1);
  const TimeNs after = RealtimeNow();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].edge, Edge::kRising);
  EXPECT_EQ(events[0].sequence, 0u);
  EXPECT_GE(events[0].time_ns, before - kNsPerMs);
  EXPECT_LE(events[0].time_ns, after + kNsPerMs);

  ASSERT_TRUE(sim_->Pull(1, false).ok());  // falling: not requested
  EXPECT_FALSE(*input->Wait(200 * kNsPerMs));
  std::array<EdgeEvent, 4> buffer{};
  EXPECT_EQ(*input->Read(buffer), 0u) << "Read never blocks";

  ASSERT_TRUE(sim_->Pull(1, true).ok());
  events = ReadUntil(*input, 1);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].sequence, 1u);
}

TEST_F(LibgpiodSimTest, BothEdgesOnAnActiveLowLineAreLogicalEdges) {
  EdgeInputOptions options{.line = Line(2), .edges = EdgeSelection::kBoth, .active_low = true};
  auto input = LibgpiodEdgeInput::Open(options);
  ASSERT_TRUE(input.ok()) << input.error().message;
  std::vector<EdgeEvent> events;
  for (int i = 0; i < 6; ++i) {
    ASSERT_TRUE(sim_->Pull(2, i % 2 == 0).ok());
    events = ReadUntil(*input, static_cast<std::size_t>(i + 1), std::move(events));
  }
  ASSERT_EQ(events.size(), 6u);
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].edge, i % 2 == 0 ? Edge::kFalling : Edge::kRising) << i;
    EXPECT_EQ(events[i].sequence, i);
    if (i > 0) {
      EXPECT_GE(events[i].time_ns, events[i - 1].time_ns);
    }
  }
}

TEST_F(LibgpiodSimTest, FindsALineByName) {
  if (!sim_->has_line_names()) GTEST_SKIP() << sim_->kind() << " lines have no names";
  EdgeInputOptions options;
  options.line = {sim_->chip_name(), 0, kLineName};
  auto input = LibgpiodEdgeInput::Open(options);
  ASSERT_TRUE(input.ok()) << input.error().message;
  EXPECT_EQ(input->description(), "line 'flat2d-pps' (3) on " + sim_->chip_name());
  ASSERT_TRUE(sim_->Pull(kNamedOffset, true).ok());
  EXPECT_EQ(ReadUntil(*input, 1).size(), 1u);

  options.line.name = "flat2d-no-such-line";
  EXPECT_EQ(LibgpiodEdgeInput::Open(options).error().message,
            "no line named 'flat2d-no-such-line' on " + sim_->chip_name());
}

TEST_F(LibgpiodSimTest, OffsetBeyondTheChipIsAnError) {
  auto input = LibgpiodEdgeInput::Open({.line = Line(200)});
  ASSERT_FALSE(input.ok());
  EXPECT_EQ(input.error().message.rfind("line 200 on " + sim_->chip_name() + ": no such line", 0),
            0u)
      << input.error().message;
}

TEST_F(LibgpiodSimTest, BusyLineNamesItsConsumer) {
  auto first = LibgpiodEdgeInput::Open({.line = Line(4), .consumer = "flat2d-first"});
  ASSERT_TRUE(first.ok()) << first.error().message;
  auto second = LibgpiodEdgeInput::Open({.line = Line(4)});
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.error().message,
            "line 4 on " + sim_->chip_name() + " is busy (used by 'flat2d-first')");
}

TEST_F(LibgpiodSimTest, OutputDrivesTheLineAndIsReleasedOnDestruction) {
  {
    auto output = LibgpiodOutput::Open({.line = Line(5), .initial_value = true});
    ASSERT_TRUE(output.ok()) << output.error().message;
    EXPECT_TRUE(output->value());
    EXPECT_TRUE(*sim_->Value(5));
    ASSERT_TRUE(output->Set(false).ok());
    EXPECT_FALSE(output->value());
    EXPECT_FALSE(*sim_->Value(5));
  }
  auto again = LibgpiodOutput::Open({.line = Line(5)});
  EXPECT_TRUE(again.ok()) << again.error().message;
}

}  // namespace
}  // namespace flat2d::hal::gpio
