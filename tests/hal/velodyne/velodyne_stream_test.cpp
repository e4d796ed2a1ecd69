// VelodyneStream on hand-built packet sequences: classification by size and port, loss,
// pauses, out-of-order packets, malformed packets, and the calibration override.
#include "hal/velodyne/velodyne_stream.hpp"

#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::hal::velodyne {
namespace {

using flat2d::testing::DataPacketBuilder;

constexpr std::uint32_t kVlp16PeriodUs = 1327;  // 12 x 110.592 us
constexpr int kVlp16AzimuthPerPacket = 480;     // 12 blocks x 0.40 deg at 10 Hz

// The i-th packet of a VLP-16 turning at 10 Hz, one return per packet at laser 0.
DataPacketBuilder Vlp16Packet(int index) {
  DataPacketBuilder packet(0x37, 0x22, (index * kVlp16AzimuthPerPacket) % 36000, 40);
  packet.Timestamp(static_cast<std::uint32_t>(index) * kVlp16PeriodUs).Record(0, 0, 5000, 1);
  return packet;
}

class StreamFixture : public ::testing::Test {
 protected:
  void Push(std::span<const std::uint8_t> payload, std::uint16_t port = kDefaultDataPort) {
    net::UdpDatagram datagram;
    datagram.destination.port = port;
    datagram.receive_time_ns = 1'700'000'000'000'000'000LL;
    datagram.payload = payload;
    stream_.Push(datagram);
  }
  void PushPackets(const std::vector<int>& indices) {
    for (int index : indices) Push(Vlp16Packet(index).bytes());
  }

  std::vector<Revolution> revolutions_;
  VelodyneStream stream_{{}, [this](const Revolution& r) { revolutions_.push_back(r); }};
};

TEST_F(StreamFixture, InOrderPacketsCountNoLoss) {
  std::vector<int> indices;
  for (int i = 0; i < 200; ++i) indices.push_back(i);  // 2.65 turns
  PushPackets(indices);
  stream_.Finish();
  const VelodyneStreamStats& stats = stream_.stats();
  EXPECT_EQ(stats.data_packets, 200u);
  EXPECT_EQ(stats.points, 200u);
  EXPECT_EQ(stats.lost_packets, 0u);
  EXPECT_EQ(stats.pauses, 0u);
  EXPECT_EQ(stats.revolutions, 1u);  // cuts after packets 74 and 149 (azimuth wraps at 360 deg)
  EXPECT_EQ(stats.partial_revolutions, 2u);
  ASSERT_EQ(revolutions_.size(), 3u);
  EXPECT_TRUE(revolutions_[1].complete);
  EXPECT_EQ(revolutions_[1].fans.size(), 75u * 24u);
}

TEST_F(StreamFixture, LossIsCountedFromTimeAndAzimuthGaps) {
  PushPackets({0, 1, 2, 3, 4, 5, 9, 10});  // packets 6, 7, 8 never arrived
  EXPECT_EQ(stream_.stats().lost_packets, 3u);
  EXPECT_EQ(stream_.stats().pauses, 0u);
}

TEST_F(StreamFixture, TimeGapWithoutAzimuthGapIsAPause) {
  PushPackets({0, 1, 2, 3, 4});
  DataPacketBuilder late = Vlp16Packet(5);
  late.Timestamp(5 * kVlp16PeriodUs + 50'000);  // the sensor sent nothing for 50 ms
  Push(late.bytes());
  EXPECT_EQ(stream_.stats().lost_packets, 0u);
  EXPECT_EQ(stream_.stats().pauses, 1u);
}

TEST_F(StreamFixture, OutOfOrderAndDuplicatePacketsAreDroppedAndCounted) {
  PushPackets({0, 1, 2, 3, 5, 4, 5, 6});
  const VelodyneStreamStats& stats = stream_.stats();
  EXPECT_EQ(stats.out_of_order, 2u);  // 4 after 5, and 5 again
  EXPECT_EQ(stats.points, 6u);        // dropped packets add no points
  EXPECT_EQ(stats.lost_packets, 1u);  // 4 counted lost when 5 came early
}

TEST_F(StreamFixture, MalformedInputIsCountedAndChangesNothing) {
  PushPackets({0, 1, 2, 3});
  const VelodyneStreamStats before = stream_.stats();
  std::vector<std::uint8_t> short_payload(1205, 0xFF);
  Push(short_payload);                                               // data port, wrong size
  Push(Vlp16Packet(4).BlockFlag(3, 0xFF, 0xDD).bytes());             // bad flag
  Push(Vlp16Packet(4).BlockAzimuth(2, 40000).bytes());               // azimuth out of range
  Push(Vlp16Packet(4).FactoryBytes(0x00, 0x22).bytes());             // unknown return mode
  std::vector<std::uint8_t> position(512, 0xEE);                     // PPS byte 0xEE
  Push(position, kDefaultPositionPort);
  std::vector<std::uint8_t> other(100, 0);
  Push(other, 5353);  // someone else's traffic
  const VelodyneStreamStats& stats = stream_.stats();
  EXPECT_EQ(stats.malformed, 5u);
  EXPECT_EQ(stats.wrong_size, 1u);
  EXPECT_EQ(stats.bad_block_flag, 1u);
  EXPECT_EQ(stats.bad_azimuth, 1u);
  EXPECT_EQ(stats.unknown_return_mode, 1u);
  EXPECT_EQ(stats.bad_position_packets, 1u);
  EXPECT_EQ(stats.ignored, 1u);
  EXPECT_EQ(stats.points, before.points);
  PushPackets({4, 5});  // and the stream goes on
  EXPECT_EQ(stream_.stats().points, before.points + 2);
  EXPECT_EQ(stream_.stats().lost_packets, 0u);
}

TEST_F(StreamFixture, IdentifiesTheModelFromTheFirstPackets) {
  PushPackets({0, 1, 2});
  EXPECT_FALSE(stream_.identification().has_value());  // still buffering
  EXPECT_EQ(stream_.stats().points, 0u);
  PushPackets({3});
  ASSERT_TRUE(stream_.identification().has_value());
  EXPECT_EQ(stream_.identification()->model, Model::kVlp16);
  EXPECT_EQ(stream_.stats().points, 4u);  // the buffered packets were decoded too
}

TEST(VelodyneStream, ShortStreamIsDecidedAtFinish) {
  VelodyneStream stream({});
  const DataPacketBuilder packet = Vlp16Packet(0);  // outlives the datagram's view of it
  net::UdpDatagram datagram;
  datagram.destination.port = kDefaultDataPort;
  datagram.payload = packet.bytes();
  stream.Push(datagram);
  stream.Finish();
  ASSERT_TRUE(stream.identification().has_value());
  EXPECT_EQ(stream.stats().points, 1u);
}

TEST(VelodyneStream, CalibrationOverridesTheBuiltInTable) {
  LaserTable table = DefaultLaserTable(Model::kVlp16);
  table.lasers[0].elevation_rad = 0.0;           // laser 0 made horizontal
  table.lasers[0].vertical_offset_m = 0.0;
  table.lasers[0].distance_offset_m = 0.5;       // and 0.5 m longer
  table.lasers[0].rot_correction_rad = std::numbers::pi / 2;  // fires 90 deg earlier
  VelodyneStreamOptions options;
  options.calibration = table;
  std::vector<LaserReturn> returns;
  VelodyneStream stream(options, [&](const Revolution& revolution) {
    for (const Fan& fan : revolution.fans) {
      if (fan.returns[0].range_m > 0.0f) returns.push_back(fan.returns[0]);
    }
  });
  net::UdpDatagram datagram;
  datagram.destination.port = kDefaultDataPort;
  DataPacketBuilder packet(0x37, 0x22, 9000, 40);  // block 0 at 90 deg
  packet.Record(0, 0, 5000, 1);
  datagram.payload = packet.bytes();
  stream.Push(datagram);
  stream.Finish();
  ASSERT_EQ(returns.size(), 1u);
  EXPECT_FLOAT_EQ(returns[0].range_m, 10.5f);
  EXPECT_NEAR(returns[0].xyz.x(), 10.5, 1e-4);  // 90 - 90 = 0 deg: straight ahead
  EXPECT_NEAR(returns[0].xyz.y(), 0.0, 1e-4);
  EXPECT_NEAR(returns[0].xyz.z(), 0.0, 1e-6);
  EXPECT_EQ(stream.identification()->decided_by, "configuration");
}

}  // namespace
}  // namespace flat2d::hal::velodyne
