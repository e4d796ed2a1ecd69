// The daemon's GPIO wiring on fake lines: the pose-valid output follows the localization
// state with the configured hold times and is off when stopping; PPS edges give the
// host clock's offset and drift in the status; configuration errors name the field; a line
// that cannot be requested stops start-up with its name.
#include "daemon/service/gpio_wiring.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "daemon/config/daemon_config.hpp"
#include "tests/hal/gpio/fake_lines.hpp"

namespace flat2d::daemon {
namespace {

using hal::gpio::Edge;
using hal::gpio::testing::FakeEdgeSource;
using hal::gpio::testing::FakeOutput;

constexpr TimeNs kMs = 1'000'000;
constexpr TimeNs kFirstPulseNs = 1'700'000'000 * kNsPerSecond;

GpioConfig PoseValidConfig(bool active_low) {
  GpioConfig config;
  PoseValidOutputConfig& output = *config.mutable_pose_valid();
  output.mutable_line()->set_chip("gpiochip0");
  output.mutable_line()->set_offset(17);
  output.set_active_low(active_low);
  output.set_min_on_ms(500);
  output.set_min_off_ms(1000);
  return config;
}

GpioConfig PpsConfig() {
  GpioConfig config;
  PpsInputConfig& pps = *config.mutable_pps();
  pps.mutable_line()->set_chip("gpiochip0");
  pps.mutable_line()->set_offset(4);
  pps.set_window_pulses(32);
  pps.set_lock_pulses(8);
  return config;
}

TEST(GpioWiring, NothingConfiguredReportsNothing) {
  auto wiring = GpioWiring::Open(GpioConfig{});
  ASSERT_TRUE(wiring.ok()) << wiring.error().message;
  (*wiring)->UpdatePoseValid(true, 0);
  EXPECT_FALSE((*wiring)->has_pps());
  EXPECT_TRUE((*wiring)->PollPps(0).ok());
  const api::v1::GpioHealth health = (*wiring)->Health(0);
  EXPECT_FALSE(health.pose_valid_configured());
  EXPECT_EQ(health.pps_state(), api::v1::PPS_NOT_CONFIGURED);
}

TEST(GpioWiring, PoseValidFollowsTheStateWithHoldTimes) {
  FakeOutput line(true);  // whatever the line was before: the wiring drives it off first
  auto wiring = GpioWiring::Create(PoseValidConfig(false), &line, nullptr);
  ASSERT_TRUE(wiring.ok()) << wiring.error().message;
  GpioWiring& gpio = **wiring;
  EXPECT_FALSE(line.value());
  gpio.UpdatePoseValid(true, 0);
  gpio.UpdatePoseValid(true, 250 * kMs);
  EXPECT_FALSE(line.value()) << "on before min_on_ms of LOCALIZED";
  gpio.UpdatePoseValid(true, 500 * kMs);
  EXPECT_TRUE(line.value());
  EXPECT_TRUE(gpio.Health(0).pose_valid_on());
  gpio.UpdatePoseValid(false, 750 * kMs);
  EXPECT_FALSE(line.value()) << "an invalid pose turns the line off at once";
  gpio.UpdatePoseValid(true, 1000 * kMs);
  gpio.UpdatePoseValid(true, 1500 * kMs);
  EXPECT_FALSE(line.value()) << "off for min_off_ms once turned off";
  gpio.UpdatePoseValid(true, 1750 * kMs);
  EXPECT_TRUE(line.value());
  EXPECT_EQ(gpio.Health(0).pose_valid_switches(), 3u);
  gpio.Stop();
  EXPECT_FALSE(line.value());
  gpio.UpdatePoseValid(true, 5000 * kMs);
  EXPECT_FALSE(line.value()) << "stopped: later updates are ignored";
}

TEST(GpioWiring, ActiveLowPoseValidDrivesTheLineLowWhenValid) {
  FakeOutput line(false);
  auto wiring = GpioWiring::Create(PoseValidConfig(true), &line, nullptr);
  ASSERT_TRUE(wiring.ok()) << wiring.error().message;
  EXPECT_TRUE(line.value()) << "off is high for an active-low line";
  (*wiring)->UpdatePoseValid(true, 0);
  (*wiring)->UpdatePoseValid(true, 600 * kMs);
  EXPECT_FALSE(line.value());
  wiring->reset();  // destroyed: the line is left in its safe state
  EXPECT_TRUE(line.value());
}

TEST(GpioWiring, FailedWritesAreCountedAndRetried) {
  FakeOutput line(false);
  auto wiring = GpioWiring::Create(PoseValidConfig(false), &line, nullptr);
  ASSERT_TRUE(wiring.ok());
  (*wiring)->UpdatePoseValid(true, 0);
  line.FailNextWrites(1);
  (*wiring)->UpdatePoseValid(true, 600 * kMs);
  EXPECT_FALSE(line.value());
  EXPECT_EQ((*wiring)->Health(0).pose_valid_write_failures(), 1u);
  (*wiring)->UpdatePoseValid(true, 850 * kMs);
  EXPECT_TRUE(line.value());
}

TEST(GpioWiring, PpsPulsesGiveTheHostClockOffsetInTheStatus) {
  // The host clock is 1.5 ms ahead of true time and runs 20 ppm fast.
  FakeEdgeSource source;
  auto wiring = GpioWiring::Create(PpsConfig(), nullptr, &source);
  ASSERT_TRUE(wiring.ok()) << wiring.error().message;
  GpioWiring& gpio = **wiring;
  ASSERT_TRUE(gpio.has_pps());
  EXPECT_EQ(gpio.Health(kFirstPulseNs).pps_state(), api::v1::PPS_NO_PULSES);
  constexpr TimeNs kOffsetNs = 1'500'000;
  constexpr double kDriftPpm = 20.0;
  auto host_at = [&](int second) {
    return kFirstPulseNs + second * kNsPerSecond + kOffsetNs + static_cast<TimeNs>(kDriftPpm * 1e3 * second);
  };
  for (int second = 0; second < 12; ++second) {
    source.Queue(host_at(second), Edge::kRising);
    source.Queue(host_at(second) + 100 * kMs, Edge::kFalling);  // requested rising only; ignored if seen
    ASSERT_TRUE(gpio.PollPps(0).ok());
  }
  const api::v1::GpioHealth health = gpio.Health(host_at(11));
  EXPECT_EQ(health.pps_state(), api::v1::PPS_LOCKED);
  EXPECT_NEAR(health.pps_offset_us(), (kOffsetNs + kDriftPpm * 1e3 * 11) * 1e-3, 0.5);
  EXPECT_NEAR(health.pps_drift_ppm(), kDriftPpm, 0.1);
  EXPECT_EQ(health.pps_pulses(), 12u);
  EXPECT_EQ(health.pps_dropped_events(), 0u);
  // Silence: the estimate is reported lost after 3 s without a pulse.
  EXPECT_EQ(gpio.Health(host_at(16)).pps_state(), api::v1::PPS_LOST);
}

TEST(GpioWiring, PpsReadFailuresAreCountedNotFatal) {
  FakeEdgeSource source;
  auto wiring = GpioWiring::Create(PpsConfig(), nullptr, &source);
  ASSERT_TRUE(wiring.ok());
  source.Queue(kFirstPulseNs, Edge::kRising);
  source.FailNextRead("line 4 on gpiochip0: Input/output error");
  const Status failed = (*wiring)->PollPps(0);
  ASSERT_FALSE(failed.ok());
  EXPECT_THAT(failed.error().message, ::testing::HasSubstr("Input/output error"));
  EXPECT_EQ((*wiring)->Health(kFirstPulseNs).pps_read_errors(), 1u);
  EXPECT_TRUE((*wiring)->PollPps(0).ok());
  EXPECT_EQ((*wiring)->Health(kFirstPulseNs).pps_pulses(), 1u);
}

TEST(GpioWiring, ALineThatCannotBeRequestedNamesIt) {
  GpioConfig config = PoseValidConfig(false);
  config.mutable_pose_valid()->mutable_line()->set_chip("gpiochip-flat2d-absent");
  auto wiring = GpioWiring::Open(config);
  ASSERT_FALSE(wiring.ok());
  EXPECT_THAT(wiring.error().message, ::testing::HasSubstr("gpio.pose_valid"));
  EXPECT_THAT(wiring.error().message, ::testing::HasSubstr("gpiochip-flat2d-absent"));
  config = PpsConfig();
  config.mutable_pps()->mutable_line()->set_chip("gpiochip-flat2d-absent");
  wiring = GpioWiring::Open(config);
  ASSERT_FALSE(wiring.ok());
  EXPECT_THAT(wiring.error().message, ::testing::HasSubstr("gpio.pps"));
}

}  // namespace
}  // namespace flat2d::daemon
