// The localization thread's inbox (daemon/service/input_queue.hpp): arrival order across the
// two rings, drops counted when full, nothing lost or reordered under two producer threads.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "daemon/service/input_queue.hpp"

namespace flat2d::daemon {
namespace {

hal::net::UdpDatagram Datagram(const std::vector<std::uint8_t>& bytes, TimeNs time_ns) {
  return {time_ns, {0xC0A801C9, 2368}, {0xFFFFFFFF, 2368}, {bytes.data(), bytes.size()}};
}

hal::can::CanFrame Frame(TimeNs time_ns, std::uint32_t id) {
  hal::can::CanFrame frame;
  frame.time_ns = time_ns;
  frame.id = id;
  return frame;
}

TEST(InputQueue, DeliversInArrivalOrderAcrossBothRings) {
  InputQueue queue(8, 8);
  const std::vector<std::uint8_t> payload(1206, 0x5A);
  queue.PushFrame(Frame(1, 0x100));
  queue.PushDatagram(Datagram(payload, 2));
  queue.PushDatagram(Datagram(payload, 3));
  queue.PushFrame(Frame(4, 0x101));
  std::vector<TimeNs> order;
  while (queue.PopNext(
      std::chrono::milliseconds(0),
      [&](const QueuedDatagram& d) {
        EXPECT_EQ(d.length, 1206);
        EXPECT_EQ(d.view().payload[1205], 0x5A);
        EXPECT_EQ(d.view().source.address, 0xC0A801C9u);
        order.push_back(d.receive_time_ns);
      },
      [&](const hal::can::CanFrame& f) { order.push_back(f.time_ns); })) {
  }
  EXPECT_EQ(order, (std::vector<TimeNs>{1, 2, 3, 4}));
}

TEST(InputQueue, AFullRingDropsTheNewItemAndCountsIt) {
  InputQueue queue(2, 1);
  const std::vector<std::uint8_t> payload(512, 1);
  EXPECT_TRUE(queue.PushDatagram(Datagram(payload, 1)));
  EXPECT_TRUE(queue.PushDatagram(Datagram(payload, 2)));
  EXPECT_FALSE(queue.PushDatagram(Datagram(payload, 3)));
  EXPECT_TRUE(queue.PushFrame(Frame(1, 1)));
  EXPECT_FALSE(queue.PushFrame(Frame(2, 1)));
  const std::vector<std::uint8_t> jumbo(kMaxQueuedDatagramBytes + 1, 0);
  EXPECT_FALSE(queue.PushDatagram(Datagram(jumbo, 4)));
  EXPECT_EQ(queue.stats().datagrams, 2u);
  EXPECT_EQ(queue.stats().datagrams_dropped, 1u);
  EXPECT_EQ(queue.stats().datagrams_too_long, 1u);
  EXPECT_EQ(queue.stats().frames_dropped, 1u);
  TimeNs first = 0;
  queue.PopNext(std::chrono::milliseconds(0), [&](const QueuedDatagram& d) { first = d.receive_time_ns; },
                [](const hal::can::CanFrame&) {});
  EXPECT_EQ(first, 1);  // the oldest stays; the newest was the one dropped
}

TEST(InputQueue, TwoProducerThreadsLoseAndReorderNothing) {
  constexpr int kItems = 20000;
  InputQueue queue(64, 64);
  const std::vector<std::uint8_t> payload(1206, 0);
  auto produce_datagrams = [&] {
    for (int i = 0; i < kItems; ++i) {
      while (!queue.PushDatagram(Datagram(payload, i))) std::this_thread::yield();
    }
  };
  auto produce_frames = [&] {
    for (int i = 0; i < kItems; ++i) {
      while (!queue.PushFrame(Frame(i, 7))) std::this_thread::yield();
    }
  };
  std::thread datagrams(produce_datagrams);
  std::thread frames(produce_frames);
  TimeNs next_datagram = 0;
  TimeNs next_frame = 0;
  bool in_order = true;
  while (next_datagram < kItems || next_frame < kItems) {
    queue.PopNext(
        std::chrono::milliseconds(100),
        [&](const QueuedDatagram& d) { in_order &= d.receive_time_ns == next_datagram++; },
        [&](const hal::can::CanFrame& f) { in_order &= f.time_ns == next_frame++; });
  }
  datagrams.join();
  frames.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(next_datagram, kItems);
  EXPECT_EQ(next_frame, kItems);
  // Drops were retried by the producers, so the counters may be non-zero; deliveries are exact.
  EXPECT_EQ(queue.stats().datagrams, static_cast<std::uint64_t>(kItems));
}

TEST(InputQueue, WakeReturnsWithoutAnItem) {
  InputQueue queue(4, 4);
  queue.Wake();
  int calls = 0;
  EXPECT_TRUE(queue.PopNext(std::chrono::milliseconds(1000), [&](const QueuedDatagram&) { ++calls; },
                            [&](const hal::can::CanFrame&) { ++calls; }));
  EXPECT_EQ(calls, 0);
  EXPECT_FALSE(queue.PopNext(std::chrono::milliseconds(1), [&](const QueuedDatagram&) { ++calls; },
                             [&](const hal::can::CanFrame&) { ++calls; }));
}

}  // namespace
}  // namespace flat2d::daemon
