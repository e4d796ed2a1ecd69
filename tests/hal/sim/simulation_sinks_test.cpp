// The live sink: real-time pacing against a fake clock, and the very bytes of the pcap
// arriving over loopback when both sinks run at once.
#include "hal/sim/simulation_sinks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "hal/net/datagram_source.hpp"
#include "hal/net/udp_receiver.hpp"
#include "tests/hal/sim/simulation_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::ScratchDir;
using testing::ShortRun;

constexpr TimeNs kClockStartNs = 5'000'000'000;

// Time advances only when the sink sleeps, so the sleeps are the schedule.
class FakeClock final : public net::ReplayClock {
 public:
  TimeNs Now() override { return now_ns_; }
  void SleepUntil(TimeNs deadline_ns) override {
    sleeps_.push_back(deadline_ns - kClockStartNs);
    now_ns_ = std::max(now_ns_, deadline_ns);
  }
  const std::vector<TimeNs>& sleeps() const { return sleeps_; }

 private:
  TimeNs now_ns_ = kClockStartNs;
  std::vector<TimeNs> sleeps_;
};

TEST(LiveSink, SendsThePcapsPacketsPacedToTheScaledCaptureTimes) {
  net::UdpReceiverOptions receiver_options;
  receiver_options.bind_address = net::kIpv4Loopback;
  receiver_options.receive_buffer_bytes = 4 << 20;
  auto receiver = net::UdpReceiver::Open(receiver_options);
  ASSERT_TRUE(receiver.ok()) << receiver.error().message;

  SimulationOptions options = ShortRun(0.1);
  options.data_port = receiver->local_endpoint().port;
  options.lidar.position_packets = false;
  FakeClock clock;
  LiveSinkOptions live_options;
  live_options.sender.destination = receiver->local_endpoint();
  live_options.speed = 2.0;
  auto live = LiveSink::Open(live_options, &clock);
  ASSERT_TRUE(live.ok()) << live.error().message;
  ScratchDir out("live");
  auto files = FileSink::Open(out.path());
  ASSERT_TRUE(files.ok()) << files.error().message;
  SimulationSink* sinks[] = {&*files, &*live};
  auto summary = RunSimulation(options, sinks);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(live->sent(), summary->data_packets);
  EXPECT_EQ(live->send_errors(), 0u);

  // Every packet after the first waits for (capture time - first capture time) / speed.
  auto capture = net::OpenCapture(out.path() / kLidarFile);
  ASSERT_TRUE(capture.ok()) << capture.error().message;
  std::vector<TimeNs> expected_sleeps;
  std::vector<std::vector<std::uint8_t>> payloads;
  TimeNs first_ns = -1;
  while (auto datagram = (*capture)->Next()) {
    if (first_ns < 0) first_ns = datagram->receive_time_ns;
    if (datagram->receive_time_ns > first_ns) {
      expected_sleeps.push_back((datagram->receive_time_ns - first_ns + 1) / 2);
    }
    payloads.emplace_back(datagram->payload.begin(), datagram->payload.end());
  }
  ASSERT_EQ(clock.sleeps().size(), expected_sleeps.size());
  for (std::size_t i = 0; i < expected_sleeps.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(clock.sleeps()[i]), static_cast<double>(expected_sleeps[i]), 1.0);
  }

  std::vector<std::vector<std::uint8_t>> received;
  for (int poll = 0; poll < 50 && received.size() < payloads.size(); ++poll) {
    for (const net::UdpDatagram& datagram : receiver->ReceiveBatch(200)) {
      received.emplace_back(datagram.payload.begin(), datagram.payload.end());
    }
  }
  EXPECT_TRUE(received == payloads) << received.size() << " of " << payloads.size() << " received";
}

}  // namespace
}  // namespace flat2d::hal::sim
