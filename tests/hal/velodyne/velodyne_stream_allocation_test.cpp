// Fixed memory: once the model is identified and the revolution buffers exist, pushing
// data packets through VelodyneStream must not touch the heap. Counts every operator new
// in this test binary.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/testing/allocation_counter.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::hal::velodyne {
namespace {

using flat2d::testing::AdvanceDeviceTime;

// Every datagram of a capture, payloads and destination ports.
struct Recording {
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<std::uint16_t> ports;
};

Recording Load(const std::filesystem::path& path) {
  Recording recording;
  auto source = net::OpenCapture(path);
  EXPECT_TRUE(source.ok());
  if (!source.ok()) return recording;
  while (auto datagram = (*source)->Next()) {
    recording.payloads.emplace_back(datagram->payload.begin(), datagram->payload.end());
    recording.ports.push_back(datagram->destination.port);
  }
  return recording;
}

// Pushes the recording `laps` times, device times moving on by `lap_us` each lap, and
// returns the heap allocations made after the first (warm-up) lap.
std::uint64_t AllocationsOverLaps(VelodyneStream& stream, Recording& recording, std::uint32_t lap_us,
                                  int laps) {
  std::uint64_t before = 0;
  net::UdpDatagram datagram;
  for (int lap = 0; lap <= laps; ++lap) {
    if (lap == 1) before = flat2d::testing::AllocationCount();
    for (std::size_t i = 0; i < recording.payloads.size(); ++i) {
      datagram.payload = recording.payloads[i];
      datagram.destination.port = recording.ports[i];
      stream.Push(datagram);
    }
    for (auto& payload : recording.payloads) AdvanceDeviceTime(payload, lap_us);
  }
  return flat2d::testing::AllocationCount() - before;
}

TEST(VelodyneStreamMemory, SteadyStateDecodingAllocatesNothing) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap");
  Recording recording = Load(path);  // 876 data and 100 position packets
  ASSERT_EQ(recording.payloads.size(), 976u);
  std::uint64_t revolutions = 0;
  VelodyneStream stream({}, [&](const Revolution& revolution) { revolutions += revolution.complete; });
  // 0.48 s of capture: one lap moves device time on by its length (876 x 553 us).
  const std::uint64_t allocations = AllocationsOverLaps(stream, recording, 876 * 553, 20);
  EXPECT_EQ(allocations, 0u) << "heap allocations over 20 laps of 976 datagrams";
  EXPECT_GE(revolutions, 100u);  // 5.7 turns a lap: the assembler really cycled its buffers
  EXPECT_EQ(stream.stats().position_packets, 21u * 100u);
  EXPECT_EQ(stream.stats().out_of_order, 0u);
  EXPECT_EQ(stream.stats().dropped_fans, 0u);
}

TEST(VelodyneStreamMemory, DualReturnStreamAllocatesNothing) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap");
  Recording recording = Load(path);
  ASSERT_EQ(recording.payloads.size(), 603u);
  VelodyneStream stream({});
  EXPECT_EQ(AllocationsOverLaps(stream, recording, 603 * 664, 10), 0u);
  EXPECT_EQ(stream.stats().revolutions, 43u);  // 4 turns a lap over 11 laps, first cut at lap 1
}

}  // namespace
}  // namespace flat2d::hal::velodyne
