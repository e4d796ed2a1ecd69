// Fixed memory: once the model is identified and the revolution buffers exist, pushing
// data packets through VelodyneStream must not touch the heap. Counts every operator new
// in this test binary.
#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include <gtest/gtest.h>

#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/testing/data_path.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace flat2d::hal::velodyne {
namespace {

void AdvanceTimestamp(std::vector<std::uint8_t>& packet, std::uint32_t by_us) {
  const std::uint32_t now = (ReadU32(packet.data() + kTimestampOffset) + by_us) % 3'600'000'000u;
  for (std::size_t i = 0; i < 4; ++i) packet[kTimestampOffset + i] = static_cast<std::uint8_t>(now >> (8 * i));
}

TEST(VelodyneStreamMemory, SteadyStateDecodingAllocatesNothing) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap");
  auto source = net::OpenCapture(path);
  ASSERT_TRUE(source.ok());
  std::vector<std::vector<std::uint8_t>> packets;
  while (auto datagram = (*source)->Next()) {
    if (datagram->payload.size() == kDataPacketSize) packets.emplace_back(datagram->payload.begin(), datagram->payload.end());
  }
  ASSERT_EQ(packets.size(), 876u);
  const std::uint32_t lap_us = ReadU32(packets.back().data() + kTimestampOffset) -
                               ReadU32(packets.front().data() + kTimestampOffset) + 553;

  std::size_t revolutions = 0;
  VelodyneStream stream({}, [&](const Revolution& revolution) { revolutions += revolution.complete; });
  net::UdpDatagram datagram;
  datagram.destination.port = kDefaultDataPort;
  auto push_lap = [&] {
    for (const auto& packet : packets) {
      datagram.payload = packet;
      stream.Push(datagram);
    }
  };
  push_lap();  // warm-up: identification, decoder tables, revolution buffers
  for (auto& packet : packets) AdvanceTimestamp(packet, lap_us);

  const std::size_t before = g_allocations.load();
  for (int lap = 0; lap < 20; ++lap) {
    push_lap();
    for (auto& packet : packets) AdvanceTimestamp(packet, lap_us);  // no allocation either
  }
  const std::size_t allocations = g_allocations.load() - before;
  EXPECT_EQ(allocations, 0u) << "heap allocations over 20 x 876 packets";
  EXPECT_GE(revolutions, 100u);  // 5.7 turns a lap: the assembler really cycled its buffers
  EXPECT_EQ(stream.stats().out_of_order, 0u);
  EXPECT_EQ(stream.stats().dropped_fans, 0u);
}

}  // namespace
}  // namespace flat2d::hal::velodyne
