// Replay schedules against a fake clock, plus one real replay over loopback.
#include "hal/net/replay.hpp"

#include <gtest/gtest.h>

#include "hal/net/udp_receiver.hpp"
#include "hal/net/udp_sender.hpp"
#include "tests/hal/net/capture_images.hpp"

namespace flat2d::hal::net {
namespace {

using testing::Bytes;

constexpr TimeNs kClockStartNs = 5'000'000'000;
constexpr TimeNs kCaptureStartNs = 1'673'400'471'000'000'000;

// Time advances only when Replay sleeps, so the sleeps are the schedule.
class FakeClock final : public ReplayClock {
 public:
  TimeNs Now() override { return now_ns_; }
  void SleepUntil(TimeNs deadline_ns) override {
    sleeps_.push_back(deadline_ns - kClockStartNs);
    now_ns_ = std::max(now_ns_, deadline_ns);
  }
  const std::vector<TimeNs>& sleeps() const { return sleeps_; }  // offsets from the start

 private:
  TimeNs now_ns_ = kClockStartNs;
  std::vector<TimeNs> sleeps_;
};

class VectorSource final : public DatagramSource {
 public:
  void Add(TimeNs time_ns, std::uint16_t port, std::uint8_t tag) {
    payloads_.push_back(Bytes{tag});
    times_.push_back(time_ns);
    ports_.push_back(port);
  }
  std::optional<UdpDatagram> Next() override {
    if (next_ >= payloads_.size()) return std::nullopt;
    const std::size_t i = next_++;
    return UdpDatagram{times_[i], {0x7F000001, 2368}, {0x7F000001, ports_[i]}, payloads_[i]};
  }
  const CaptureStats& stats() const override { return stats_; }
  std::string Describe() const override { return "vector"; }

 private:
  std::vector<Bytes> payloads_;
  std::vector<TimeNs> times_;
  std::vector<std::uint16_t> ports_;
  std::size_t next_ = 0;
  CaptureStats stats_;
};

// Records each datagram's tag with the clock time it was sent at; fails on request.
class RecordingSink final : public DatagramSink {
 public:
  explicit RecordingSink(ReplayClock& clock, std::uint8_t failing_tag = 0xFF)
      : clock_(clock), failing_tag_(failing_tag) {}
  Status Send(const UdpDatagram& datagram) override {
    if (datagram.payload[0] == failing_tag_) return MakeError("refused");
    tags.push_back(datagram.payload[0]);
    send_offsets_ns.push_back(clock_.Now() - kClockStartNs);
    return Status::Ok();
  }
  std::vector<std::uint8_t> tags;
  std::vector<TimeNs> send_offsets_ns;

 private:
  ReplayClock& clock_;
  std::uint8_t failing_tag_;
};

// Data at 0, 10, 30, 31 ms; one position packet at 20 ms.
VectorSource SampleSource() {
  VectorSource source;
  source.Add(kCaptureStartNs, 2368, 0);
  source.Add(kCaptureStartNs + 10 * kNsPerMs, 2368, 1);
  source.Add(kCaptureStartNs + 20 * kNsPerMs, 8308, 2);
  source.Add(kCaptureStartNs + 30 * kNsPerMs, 2368, 3);
  source.Add(kCaptureStartNs + 31 * kNsPerMs, 2368, 4);
  return source;
}

TEST(Replay, KeepsTheCaptureTimingAtSpeedOne) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock);
  const ReplayStats stats = Replay(source, sink, clock, {});
  EXPECT_EQ(clock.sleeps(), (std::vector<TimeNs>{10 * kNsPerMs, 20 * kNsPerMs, 30 * kNsPerMs,
                                                 31 * kNsPerMs}));
  EXPECT_EQ(sink.send_offsets_ns, (std::vector<TimeNs>{0, 10 * kNsPerMs, 20 * kNsPerMs,
                                                       30 * kNsPerMs, 31 * kNsPerMs}));
  EXPECT_EQ(stats.sent, 5u);
  EXPECT_EQ(stats.send_errors + stats.skipped, 0u);
}

TEST(Replay, HalvesTheGapsAtSpeedTwo) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock);
  ReplayOptions options;
  options.speed = 2.0;
  Replay(source, sink, clock, options);
  EXPECT_EQ(clock.sleeps(), (std::vector<TimeNs>{5 * kNsPerMs, 10 * kNsPerMs, 15 * kNsPerMs,
                                                 15'500'000}));
}

TEST(Replay, NeverSleepsAtSpeedZero) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock);
  ReplayOptions options;
  options.speed = 0;
  EXPECT_EQ(Replay(source, sink, clock, options).sent, 5u);
  EXPECT_TRUE(clock.sleeps().empty());
}

TEST(Replay, FiltersByDestinationPort) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock);
  ReplayOptions options;
  options.destination_ports = {8308};
  const ReplayStats stats = Replay(source, sink, clock, options);
  EXPECT_EQ(sink.tags, (std::vector<std::uint8_t>{2}));
  EXPECT_EQ(stats.skipped, 4u);
  EXPECT_TRUE(clock.sleeps().empty());  // the schedule starts at the first selected one
}

TEST(Replay, StopsAtTheCountAndDurationLimits) {
  {
    VectorSource source = SampleSource();
    FakeClock clock;
    RecordingSink sink(clock);
    ReplayOptions options;
    options.max_datagrams = 2;
    EXPECT_EQ(Replay(source, sink, clock, options).sent, 2u);
  }
  {
    VectorSource source = SampleSource();
    FakeClock clock;
    RecordingSink sink(clock);
    ReplayOptions options;
    options.max_duration_ns = 20 * kNsPerMs;  // inclusive: 0, 10 and 20 ms
    Replay(source, sink, clock, options);
    EXPECT_EQ(sink.tags, (std::vector<std::uint8_t>{0, 1, 2}));
  }
}

TEST(Replay, WithholdsAnOutageAndResumesOnTime) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock);
  ReplayOptions options;
  options.outage_from_ns = 10 * kNsPerMs;  // 10 and 20 ms are withheld, 30 ms is not
  options.outage_ns = 20 * kNsPerMs;
  const ReplayStats stats = Replay(source, sink, clock, options);
  EXPECT_EQ(sink.tags, (std::vector<std::uint8_t>{0, 3, 4}));
  EXPECT_EQ(sink.send_offsets_ns, (std::vector<TimeNs>{0, 30 * kNsPerMs, 31 * kNsPerMs}));
  EXPECT_EQ(stats.withheld, 2u);
  EXPECT_EQ(stats.sent, 3u);
}

TEST(Replay, CountsSendErrorsAndGoesOn) {
  VectorSource source = SampleSource();
  FakeClock clock;
  RecordingSink sink(clock, /*failing_tag=*/1);
  const ReplayStats stats = Replay(source, sink, clock, {});
  EXPECT_EQ(stats.sent, 4u);
  EXPECT_EQ(stats.send_errors, 1u);
  EXPECT_EQ(stats.first_send_error, "refused");
}

TEST(Replay, PacesUntimedSourcesAtTheGivenInterval) {
  VectorSource source;
  for (std::uint8_t i = 0; i < 4; ++i) source.Add(0, 2368, i);
  FakeClock clock;
  RecordingSink sink(clock);
  ReplayOptions options;
  options.untimed_interval_ns = 1'327'000;  // VLP-16 packet period
  Replay(source, sink, clock, options);
  EXPECT_EQ(clock.sleeps(), (std::vector<TimeNs>{1'327'000, 2'654'000, 3'981'000}));
}

TEST(Replay, SendsARealCaptureOverLoopback) {
  UdpReceiverOptions receiver_options;
  receiver_options.bind_address = kIpv4Loopback;
  Result<UdpReceiver> receiver = UdpReceiver::Open(receiver_options);
  ASSERT_TRUE(receiver.ok()) << receiver.error().message;
  UdpSenderOptions sender_options;
  sender_options.destination = receiver->local_endpoint();
  sender_options.keep_datagram_port = false;
  Result<UdpSender> sender = UdpSender::Open(sender_options);
  ASSERT_TRUE(sender.ok()) << sender.error().message;
  VectorSource source = SampleSource();
  MonotonicReplayClock clock;
  ReplayOptions options;
  options.speed = 100;  // 31 ms of capture in ~0.3 ms
  const TimeNs start_ns = clock.Now();
  const ReplayStats stats = Replay(source, *sender, clock, options);
  EXPECT_GE(clock.Now() - start_ns, 310'000);  // it did wait for the schedule
  EXPECT_EQ(stats.sent, 5u);
  std::vector<std::uint8_t> tags;
  for (int poll = 0; poll < 50 && tags.size() < 5; ++poll) {
    for (const UdpDatagram& datagram : receiver->ReceiveBatch(200)) {
      tags.push_back(datagram.payload[0]);
    }
  }
  EXPECT_EQ(tags, (std::vector<std::uint8_t>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace flat2d::hal::net
