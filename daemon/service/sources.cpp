#include "daemon/service/sources.hpp"

#include <poll.h>

#include <array>
#include <chrono>
#include <thread>
#include <vector>

#include "hal/net/ipv4.hpp"

namespace flat2d::daemon {
namespace {

constexpr int kPollMs = 100;

// The data socket and, on its own port, the position socket, drained as they become readable.
class UdpLidarThread final : public SourceThread {
 public:
  explicit UdpLidarThread(std::vector<hal::net::UdpReceiver> receivers) : receivers_(std::move(receivers)) {}
  void Run(std::stop_token stop, InputQueue& queue) override {
    std::array<pollfd, 2> waits{};
    for (std::size_t i = 0; i < receivers_.size(); ++i) waits[i] = {receivers_[i].fd(), POLLIN, 0};
    while (!stop.stop_requested()) {
      Beat();
      if (::poll(waits.data(), receivers_.size(), kPollMs) <= 0) continue;
      std::uint64_t drops = 0;
      for (std::size_t i = 0; i < receivers_.size(); ++i) {
        if ((waits[i].revents & POLLIN) != 0) {
          for (const hal::net::UdpDatagram& datagram : receivers_[i].ReceiveBatch(0)) queue.PushDatagram(datagram);
        }
        drops += receivers_[i].stats().kernel_drops + receivers_[i].stats().truncated;
      }
      drops_.store(drops, std::memory_order_relaxed);
    }
  }
  std::uint64_t source_drops() const override { return drops_.load(std::memory_order_relaxed); }

 private:
  std::vector<hal::net::UdpReceiver> receivers_;  // data, then position (when on its own port)
  std::atomic<std::uint64_t> drops_{0};
};

// Sleeps in steps of at most kPollMs so the heartbeat keeps beating through long gaps. A
// capture is not a sensor: when the localization thread falls behind and the ring is full,
// the replay waits for room instead of dropping, then catches up with the recorded pace.
// A replay loses nothing, whatever else shares the CPU.
class CaptureReplayThread final : public SourceThread {
 public:
  CaptureReplayThread(std::unique_ptr<hal::net::DatagramSource> capture, double rate)
      : capture_(std::move(capture)), rate_(rate) {}
  void Run(std::stop_token stop, InputQueue& queue) override {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point wall_start = Clock::now();
    TimeNs first_ns = -1;
    while (!stop.stop_requested()) {
      Beat();
      const std::optional<hal::net::UdpDatagram> datagram = capture_->Next();
      if (!datagram) break;
      if (first_ns < 0) first_ns = datagram->receive_time_ns;
      const auto due = wall_start + std::chrono::nanoseconds(static_cast<TimeNs>(
                                        static_cast<double>(datagram->receive_time_ns - first_ns) / rate_));
      while (!stop.stop_requested() && Clock::now() < due) {
        Beat();
        std::this_thread::sleep_until(std::min(due, Clock::now() + std::chrono::milliseconds(kPollMs)));
      }
      while (!stop.stop_requested() && !queue.HasDatagramRoom()) {
        Beat();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      queue.PushDatagram(*datagram);
    }
    Finish();
  }
  std::uint64_t source_drops() const override { return 0; }

 private:
  std::unique_ptr<hal::net::DatagramSource> capture_;
  double rate_;
};

class SocketCanThread final : public SourceThread {
 public:
  explicit SocketCanThread(hal::can::SocketCanSource source) : source_(std::move(source)) {}
  void Run(std::stop_token stop, InputQueue& queue) override {
    hal::can::CanFrame frame;
    while (!stop.stop_requested()) {
      Beat();
      if (source_.Next(frame)) queue.PushFrame(frame);
      drops_.store(source_.stats().kernel_drops, std::memory_order_relaxed);
    }
  }
  std::uint64_t source_drops() const override { return drops_.load(std::memory_order_relaxed); }

 private:
  hal::can::SocketCanSource source_;
  std::atomic<std::uint64_t> drops_{0};
};

}  // namespace

hal::velodyne::VelodyneStreamOptions StreamOptionsFor(const LidarSource& config) {
  hal::velodyne::VelodyneStreamOptions options;
  if (config.has_udp()) {
    options.data_port = static_cast<std::uint16_t>(config.udp().port());
    options.position_port = static_cast<std::uint16_t>(config.udp().position_port());
  }
  return options;
}

Result<std::unique_ptr<SourceThread>> OpenLidarSource(const LidarSource& config) {
  if (config.has_pcap()) {
    auto capture = hal::net::OpenCapture(config.pcap().path());
    if (!capture.ok()) return capture.error();
    return std::unique_ptr<SourceThread>(std::make_unique<CaptureReplayThread>(std::move(*capture), config.pcap().rate()));
  }
  hal::net::UdpReceiverOptions options;
  options.bind_address = *hal::net::ParseIpv4(config.udp().bind_address());  // validated with the config
  options.port = static_cast<std::uint16_t>(config.udp().port());
  options.receive_buffer_bytes = static_cast<int>(config.udp().receive_buffer_bytes());
  if (!config.udp().sensor_address().empty()) options.source_filter = hal::net::ParseIpv4(config.udp().sensor_address());
  std::vector<hal::net::UdpReceiver> receivers;
  auto data = hal::net::UdpReceiver::Open(options);
  if (!data.ok()) return data.error();
  receivers.push_back(std::move(*data));
  if (config.udp().position_port() != config.udp().port()) {
    options.port = static_cast<std::uint16_t>(config.udp().position_port());
    options.receive_buffer_bytes = 0;  // one packet a second
    auto position = hal::net::UdpReceiver::Open(options);
    if (!position.ok()) return position.error();
    receivers.push_back(std::move(*position));
  }
  return std::unique_ptr<SourceThread>(std::make_unique<UdpLidarThread>(std::move(receivers)));
}

Result<std::unique_ptr<SourceThread>> OpenCanSource(const CanSource& config) {
  if (!config.has_socketcan()) return std::unique_ptr<SourceThread>();
  hal::can::SocketCanOptions options;
  options.interface_name = config.socketcan().interface();
  options.timeout_ms = kPollMs;
  auto source = hal::can::SocketCanSource::Open(options);
  if (!source.ok()) return source.error();
  return std::unique_ptr<SourceThread>(std::make_unique<SocketCanThread>(std::move(*source)));
}

}  // namespace flat2d::daemon
