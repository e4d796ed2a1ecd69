// The LiDAR source threads (daemon/service/sources.hpp): a capture replay loses nothing when
// the localization thread falls behind; it waits for room in the ring instead.
#include "daemon/service/sources.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>
#include <unistd.h>
#include <vector>

#include "hal/net/pcap_writer.hpp"

namespace flat2d::daemon {
namespace {

constexpr int kDatagrams = 300;

// kDatagrams datagrams 1 ms apart, each carrying its index in its first two bytes.
std::filesystem::path WriteCapture() {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("flat2d_sources_test_" + std::to_string(::getpid()) + ".pcap");
  auto writer = hal::net::PcapWriter::Create(path);
  EXPECT_TRUE(writer.ok()) << writer.error().message;
  std::vector<std::uint8_t> payload(1206, 0);
  for (int i = 0; i < kDatagrams; ++i) {
    payload[0] = static_cast<std::uint8_t>(i & 0xFF);
    payload[1] = static_cast<std::uint8_t>(i >> 8);
    const hal::net::UdpDatagram datagram{1'000'000'000 + i * 1'000'000, {0xC0A801C9, 2368}, {0xFFFFFFFF, 2368},
                                         {payload.data(), payload.size()}};
    EXPECT_TRUE(writer->Write(datagram).ok());
  }
  EXPECT_TRUE(writer->Close().ok());
  return path;
}

// Replayed at 100x into a ring of 4 slots while the consumer takes 1 ms per datagram (ten
// times the replay's pace): every datagram arrives, in order, and none is counted dropped.
TEST(CaptureReplay, ASlowConsumerLosesNothing) {
  const std::filesystem::path path = WriteCapture();
  LidarSource config;
  config.mutable_pcap()->set_path(path.string());
  config.mutable_pcap()->set_rate(100.0);
  auto source = OpenLidarSource(config);
  ASSERT_TRUE(source.ok()) << source.error().message;
  InputQueue queue(4, 4);
  std::jthread replay([&](std::stop_token stop) { (*source)->Run(stop, queue); });
  std::vector<int> received;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (static_cast<int>(received.size()) < kDatagrams && std::chrono::steady_clock::now() < deadline) {
    queue.PopNext(
        std::chrono::milliseconds(100),
        [&](const QueuedDatagram& d) { received.push_back(d.bytes[0] | (d.bytes[1] << 8)); },
        [](const hal::can::CanFrame&) {});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  replay.request_stop();
  replay.join();
  std::filesystem::remove(path);
  ASSERT_EQ(static_cast<int>(received.size()), kDatagrams);
  for (int i = 0; i < kDatagrams; ++i) ASSERT_EQ(received[static_cast<std::size_t>(i)], i);
  EXPECT_EQ(queue.stats().datagrams_dropped.load(), 0u);
  EXPECT_TRUE((*source)->finished());
}

}  // namespace
}  // namespace flat2d::daemon
