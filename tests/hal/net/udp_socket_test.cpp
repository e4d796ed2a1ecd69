// UdpReceiver and UdpSender over loopback (127.0.0.0/8 only), with bounded waits.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "hal/net/udp_receiver.hpp"
#include "hal/net/udp_sender.hpp"
#include "tests/hal/net/capture_images.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::net {
namespace {

constexpr std::uint32_t kLoopback2 = 0x7F000002;  // 127.0.0.2: a second local "host"
constexpr int kPollMs = 200;
constexpr int kMaxPolls = 50;  // bounds every receive loop at ~10 s

UdpReceiver OpenReceiver(UdpReceiverOptions options) {
  options.bind_address = kIpv4Loopback;
  Result<UdpReceiver> receiver = UdpReceiver::Open(options);
  EXPECT_TRUE(receiver.ok()) << (receiver.ok() ? "" : receiver.error().message);
  return std::move(receiver).value();
}

UdpSender OpenSender(const Ipv4Endpoint& destination, std::uint32_t bind_address = kIpv4Any) {
  UdpSenderOptions options;
  options.destination = destination;
  options.bind_address = bind_address;
  Result<UdpSender> sender = UdpSender::Open(options);
  EXPECT_TRUE(sender.ok()) << (sender.ok() ? "" : sender.error().message);
  return std::move(sender).value();
}

// Receives until `wanted` datagrams arrived or the poll budget is spent.
std::vector<UdpDatagram> ReceiveUpTo(UdpReceiver& receiver, std::size_t wanted,
                                     std::vector<testing::Bytes>& payloads) {
  std::vector<UdpDatagram> received;
  for (int poll = 0; poll < kMaxPolls && received.size() < wanted; ++poll) {
    for (const UdpDatagram& datagram : receiver.ReceiveBatch(kPollMs)) {
      received.push_back(datagram);
      payloads.push_back(testing::PayloadOf(datagram));  // views die at the next batch
    }
  }
  return received;
}

TimeNs RealtimeNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Linux enables receive timestamping lazily (see udp_receiver.hpp): until it is on,
// datagrams are stamped when read. Waits until a probe's stamp predates a pause
// between sending and reading it, i.e. the kernel stamped it on arrival.
bool WaitUntilStampedOnArrival(UdpReceiver& receiver, UdpSender& sender) {
  constexpr auto kPause = std::chrono::milliseconds(5);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const TimeNs sent_ns = RealtimeNowNs();
    if (!sender.SendPayload(testing::CountingPayload(1))) return false;
    std::this_thread::sleep_for(kPause);
    const std::span<const UdpDatagram> probe = receiver.ReceiveBatch(kPollMs);
    if (probe.size() == 1 && probe[0].receive_time_ns < sent_ns + kPause.count() * 1'000'000 / 2) {
      return true;
    }
  }
  return false;
}

TEST(UdpReceiver, ReceivesEverythingSentWithMonotonicKernelTimestamps) {
  UdpReceiverOptions options;
  options.batch_size = 16;
  options.receive_buffer_bytes = 4 << 20;  // the whole burst below must fit
  UdpReceiver receiver = OpenReceiver(options);
  UdpSender sender = OpenSender(receiver.local_endpoint());
  ASSERT_TRUE(WaitUntilStampedOnArrival(receiver, sender));
  const std::uint64_t probes = receiver.stats().received;
  constexpr int kCount = 200;
  for (int i = 0; i < kCount; ++i) {
    ASSERT_TRUE(sender.SendPayload(testing::CountingPayload(1206, static_cast<std::uint8_t>(i))));
  }
  std::vector<testing::Bytes> payloads;
  const std::vector<UdpDatagram> received = ReceiveUpTo(receiver, kCount, payloads);
  ASSERT_EQ(received.size(), static_cast<std::size_t>(kCount));
  for (int i = 0; i < kCount; ++i) {
    SCOPED_TRACE("datagram " + std::to_string(i));
    EXPECT_EQ(payloads[i], testing::CountingPayload(1206, static_cast<std::uint8_t>(i)));
    EXPECT_GT(received[i].receive_time_ns, 1'600'000'000LL * kNsPerSecond);  // after 2020
    if (i > 0) {
      EXPECT_GE(received[i].receive_time_ns, received[i - 1].receive_time_ns);
    }
    EXPECT_EQ(received[i].source.address, kIpv4Loopback);
    EXPECT_EQ(received[i].source.port, sender.local_endpoint().port);
    EXPECT_EQ(received[i].destination.address, kIpv4Loopback);
    EXPECT_EQ(received[i].destination.port, receiver.local_endpoint().port);
  }
  EXPECT_EQ(receiver.stats().received, probes + kCount);
  EXPECT_EQ(receiver.stats().without_kernel_time, 0u);
  EXPECT_EQ(receiver.stats().kernel_drops, 0u);
  EXPECT_EQ(receiver.stats().errors, 0u);
}

TEST(UdpReceiver, SourceFilterDropsOtherHosts) {
  UdpReceiverOptions options;
  options.source_filter = kIpv4Loopback;
  UdpReceiver receiver = OpenReceiver(options);
  UdpSender wanted = OpenSender(receiver.local_endpoint(), kIpv4Loopback);
  UdpSender other = OpenSender(receiver.local_endpoint(), kLoopback2);
  ASSERT_EQ(other.local_endpoint().address, kLoopback2);
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(other.SendPayload(testing::CountingPayload(64, 0xA0)));
    ASSERT_TRUE(wanted.SendPayload(testing::CountingPayload(64, static_cast<std::uint8_t>(i))));
  }
  std::vector<testing::Bytes> payloads;
  const std::vector<UdpDatagram> received = ReceiveUpTo(receiver, 10, payloads);
  ASSERT_EQ(received.size(), 10u);
  for (const UdpDatagram& datagram : received) EXPECT_EQ(datagram.source.address, kIpv4Loopback);
  for (std::size_t i = 0; i < payloads.size(); ++i) EXPECT_EQ(payloads[i][0], i);
  EXPECT_EQ(receiver.stats().filtered_by_source, 10u);
}

TEST(UdpReceiver, CountsAndDropsOversizeDatagrams) {
  UdpReceiverOptions options;
  options.max_datagram_bytes = 600;
  UdpReceiver receiver = OpenReceiver(options);
  UdpSender sender = OpenSender(receiver.local_endpoint());
  ASSERT_TRUE(sender.SendPayload(testing::CountingPayload(1206)));
  ASSERT_TRUE(sender.SendPayload(testing::CountingPayload(512)));
  std::vector<testing::Bytes> payloads;
  const std::vector<UdpDatagram> received = ReceiveUpTo(receiver, 1, payloads);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(payloads[0], testing::CountingPayload(512));
  EXPECT_EQ(receiver.stats().truncated, 1u);
}

TEST(UdpReceiver, AppliesTheRequestedReceiveBuffer) {
  UdpReceiverOptions options;
  options.receive_buffer_bytes = 1 << 20;
  const UdpReceiver receiver = OpenReceiver(options);
  EXPECT_GE(receiver.receive_buffer_bytes(), 1 << 20);
}

TEST(UdpReceiver, ReportsKernelDropsFromAFullReceiveBuffer) {
  UdpReceiverOptions options;
  options.receive_buffer_bytes = 1;  // the kernel rounds up to its minimum (a few KiB)
  UdpReceiver receiver = OpenReceiver(options);
  UdpSender sender = OpenSender(receiver.local_endpoint());
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(sender.SendPayload(testing::CountingPayload(1206)));
  // Drain what fit, then send one more: it carries the drop counter for sure.
  for (int poll = 0; poll < kMaxPolls && !receiver.ReceiveBatch(20).empty(); ++poll) {
  }
  ASSERT_TRUE(sender.SendPayload(testing::CountingPayload(10)));
  std::vector<testing::Bytes> payloads;
  ReceiveUpTo(receiver, 1, payloads);
  ASSERT_EQ(payloads.size(), 1u);
  EXPECT_LT(receiver.stats().received, 101u);
  EXPECT_EQ(receiver.stats().kernel_drops, 101u - receiver.stats().received);
}

TEST(UdpReceiver, ReceiveBatchDoesNotAllocate) {
  UdpReceiver receiver = OpenReceiver({});
  UdpSender sender = OpenSender(receiver.local_endpoint());
  const testing::Bytes payload = testing::CountingPayload(1206);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(sender.SendPayload(payload));
  std::size_t received = 0;
  const std::uint64_t allocations_before = flat2d::testing::AllocationCount();
  for (int poll = 0; poll < kMaxPolls && received < 20; ++poll) {
    received += receiver.ReceiveBatch(kPollMs).size();
  }
  const std::uint64_t allocations = flat2d::testing::AllocationCount() - allocations_before;
  EXPECT_EQ(received, 20u);
  EXPECT_EQ(allocations, 0u);
}

TEST(UdpReceiver, ReturnsNothingAfterTheTimeout) {
  UdpReceiver receiver = OpenReceiver({});
  EXPECT_TRUE(receiver.ReceiveBatch(10).empty());
  EXPECT_EQ(receiver.stats().errors, 0u);
}

TEST(UdpReceiver, ExplainsABindConflict) {
  const UdpReceiver first = OpenReceiver({});
  UdpReceiverOptions options;
  options.bind_address = kIpv4Loopback;
  options.port = first.local_endpoint().port;
  const Result<UdpReceiver> second = UdpReceiver::Open(options);
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.error().message, "cannot bind " + FormatEndpoint(first.local_endpoint()) +
                                        ": Address already in use");
}

TEST(UdpReceiver, RefusesImpossibleOptions) {
  UdpReceiverOptions options;
  options.bind_address = kIpv4Loopback;
  options.batch_size = 0;
  EXPECT_FALSE(UdpReceiver::Open(options).ok());
  options.batch_size = 2000;
  EXPECT_FALSE(UdpReceiver::Open(options).ok());
  options.batch_size = 8;
  options.max_datagram_bytes = 70000;
  EXPECT_FALSE(UdpReceiver::Open(options).ok());
  options.max_datagram_bytes = 1500;
  options.multicast_group = kIpv4Loopback;  // not a multicast address
  const Result<UdpReceiver> receiver = UdpReceiver::Open(options);
  ASSERT_FALSE(receiver.ok());
  EXPECT_NE(receiver.error().message.find("224.0.0.0/4"), std::string::npos);
}

TEST(UdpSender, SendsADatagramToItsOwnDestinationPortUnlessToldOtherwise) {
  UdpReceiver data = OpenReceiver({});
  UdpReceiver position = OpenReceiver({});
  UdpSender sender = OpenSender({kIpv4Loopback, data.local_endpoint().port});
  const testing::Bytes payload = testing::CountingPayload(512);
  ASSERT_TRUE(sender.Send({0, {}, {kIpv4Broadcast, position.local_endpoint().port}, payload}));
  ASSERT_TRUE(sender.Send({0, {}, {kIpv4Broadcast, 0}, payload}));  // no port: the default
  std::vector<testing::Bytes> payloads;
  EXPECT_EQ(ReceiveUpTo(position, 1, payloads).size(), 1u);
  EXPECT_EQ(ReceiveUpTo(data, 1, payloads).size(), 1u);
}

TEST(UdpSender, ExplainsABindFailure) {
  const UdpReceiver taken = OpenReceiver({});
  UdpSenderOptions options;
  options.bind_address = kIpv4Loopback;
  options.bind_port = taken.local_endpoint().port;
  const Result<UdpSender> sender = UdpSender::Open(options);
  ASSERT_FALSE(sender.ok());
  EXPECT_EQ(sender.error().message,
            "cannot bind " + FormatEndpoint(taken.local_endpoint()) + ": Address already in use");
}

}  // namespace
}  // namespace flat2d::hal::net
