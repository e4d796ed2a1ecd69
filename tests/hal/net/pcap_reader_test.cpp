// PcapReader against hand-built pcap/pcapng images of every supported link type.
#include "hal/net/pcap_reader.hpp"

#include <gtest/gtest.h>

#include "tests/hal/net/capture_images.hpp"

namespace flat2d::hal::net {
namespace {

using testing::Bytes;
using testing::Record;

const Ipv4Endpoint kSensor{0xC0A801C9, 2368};     // 192.168.1.201:2368
const Ipv4Endpoint kBroadcast{0xFFFFFFFF, 2368};  // 255.255.255.255:2368

Bytes SensorPacket(std::size_t payload_size = 1206, std::uint8_t first = 0) {
  return testing::Ipv4Udp(kSensor, kBroadcast, testing::CountingPayload(payload_size, first));
}

PcapReader OpenOrDie(const Bytes& image) {
  Result<PcapReader> reader = PcapReader::OpenMemory(image);
  EXPECT_TRUE(reader.ok()) << (reader.ok() ? "" : reader.error().message);
  return std::move(reader).value();
}

// Reads one datagram from a one-record capture and checks every field.
void ExpectSingleSensorDatagram(std::uint32_t link_type, const Bytes& frame) {
  SCOPED_TRACE("link type " + std::to_string(link_type));
  const Bytes image = testing::PcapImage(link_type, {{1453364282, 709123456, frame}});
  PcapReader reader = OpenOrDie(image);
  const std::optional<UdpDatagram> datagram = reader.Next();
  ASSERT_TRUE(datagram.has_value());
  EXPECT_EQ(datagram->receive_time_ns, 1453364282LL * kNsPerSecond + 709123456);
  EXPECT_EQ(datagram->source.address, kSensor.address);
  EXPECT_EQ(datagram->source.port, kSensor.port);
  EXPECT_EQ(datagram->destination.address, kBroadcast.address);
  EXPECT_EQ(datagram->destination.port, kBroadcast.port);
  EXPECT_EQ(testing::PayloadOf(*datagram), testing::CountingPayload(1206));
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_EQ(reader.stats().frames, 1u);
  EXPECT_EQ(reader.stats().udp_datagrams, 1u);
  EXPECT_FALSE(reader.stats().file_truncated);
}

TEST(PcapReader, ReadsEthernet) {
  ExpectSingleSensorDatagram(1, testing::EthernetFrame(SensorPacket()));
}

TEST(PcapReader, ReadsVlanAndQinQTaggedEthernet) {
  ExpectSingleSensorDatagram(1, testing::EthernetFrame(SensorPacket(), 0x0800, {{0x8100, 42}}));
  ExpectSingleSensorDatagram(
      1, testing::EthernetFrame(SensorPacket(), 0x0800, {{0x88A8, 7}, {0x8100, 42}}));
}

TEST(PcapReader, ReadsLinuxCookedSllAndSll2) {
  ExpectSingleSensorDatagram(113, testing::SllFrame(SensorPacket()));
  ExpectSingleSensorDatagram(276, testing::Sll2Frame(SensorPacket()));
}

TEST(PcapReader, ReadsRawIpInAllItsLinkTypeNumbers) {
  for (const std::uint32_t link_type : {101u, 12u, 14u, 228u}) {
    ExpectSingleSensorDatagram(link_type, SensorPacket());
  }
}

TEST(PcapReader, ReadsBsdLoopbackInBothByteOrders) {
  ExpectSingleSensorDatagram(0, testing::BsdLoopbackFrame(SensorPacket(), 2, false));
  ExpectSingleSensorDatagram(0, testing::BsdLoopbackFrame(SensorPacket(), 2, true));
  ExpectSingleSensorDatagram(108, testing::BsdLoopbackFrame(SensorPacket(), 2, true));
}

TEST(PcapReader, ScalesMicrosecondTimestampsToNanoseconds) {
  const Bytes image = testing::PcapImage(
      1, {{100, 999999, testing::EthernetFrame(SensorPacket())}}, /*nanosecond=*/false);
  PcapReader reader = OpenOrDie(image);
  const std::optional<UdpDatagram> datagram = reader.Next();
  ASSERT_TRUE(datagram.has_value());
  EXPECT_EQ(datagram->receive_time_ns, 100 * kNsPerSecond + 999999 * kNsPerUs);
}

TEST(PcapReader, ReadsMinimalPcapngWithNanosecondAndMicrosecondResolution) {
  for (const bool nanosecond : {true, false}) {
    SCOPED_TRACE(nanosecond ? "if_tsresol 9" : "default resolution");
    const std::uint32_t fraction = nanosecond ? 123456789 : 123456;
    const Bytes image = testing::PcapngImage(
        1,
        {{1673400471, fraction, testing::EthernetFrame(SensorPacket(1206, 0))},
         {1673400472, fraction, testing::EthernetFrame(SensorPacket(512, 9))}},
        nanosecond);
    PcapReader reader = OpenOrDie(image);
    const std::optional<UdpDatagram> first = reader.Next();
    ASSERT_TRUE(first.has_value());
    EXPECT_EQ(first->receive_time_ns, 1673400471LL * kNsPerSecond + 123456789 -
                                          (nanosecond ? 0 : 789));
    EXPECT_EQ(testing::PayloadOf(*first), testing::CountingPayload(1206, 0));
    const std::optional<UdpDatagram> second = reader.Next();
    ASSERT_TRUE(second.has_value());
    EXPECT_EQ(testing::PayloadOf(*second), testing::CountingPayload(512, 9));
    EXPECT_FALSE(reader.Next().has_value());
    EXPECT_EQ(reader.stats().udp_datagrams, 2u);
    EXPECT_FALSE(reader.stats().file_truncated);
  }
}

TEST(PcapReader, KeepsDatagramsBeforeARecordCutByTheEndOfFile) {
  Bytes image = testing::PcapImage(1, {{1, 0, testing::EthernetFrame(SensorPacket(1206, 1))},
                                       {2, 0, testing::EthernetFrame(SensorPacket(1206, 2))},
                                       {3, 0, testing::EthernetFrame(SensorPacket(1206, 3))}});
  image.resize(image.size() - 600);  // the third record loses half its bytes
  PcapReader reader = OpenOrDie(image);
  std::vector<std::uint8_t> first_bytes;
  while (const std::optional<UdpDatagram> datagram = reader.Next()) {
    first_bytes.push_back(datagram->payload[0]);
  }
  EXPECT_EQ(first_bytes, (std::vector<std::uint8_t>{1, 2}));
  EXPECT_TRUE(reader.stats().file_truncated);
  EXPECT_NE(reader.stats().file_error.find("truncated"), std::string::npos)
      << reader.stats().file_error;
  EXPECT_FALSE(reader.Next().has_value());  // stays at the end
}

TEST(PcapReader, CountsEveryFrameThatIsNotAWholeUdpDatagram) {
  const Bytes good = SensorPacket(100);
  testing::Ipv4Shape tcp, more_fragments, later_fragment, bad_ihl, long_udp, short_udp;
  tcp.protocol = 6;
  more_fragments.flags_and_fragment_offset = 0x2000;
  later_fragment.flags_and_fragment_offset = 185;  // offset 1480 bytes, last fragment
  bad_ihl.ihl_words = 3;
  long_udp.udp_length_delta = +1;
  short_udp.udp_length_delta = -101;  // 7: shorter than the UDP header itself
  const Bytes payload = testing::CountingPayload(100);
  auto packet = [&](const testing::Ipv4Shape& shape) {
    return testing::EthernetFrame(testing::Ipv4Udp(kSensor, kBroadcast, payload, shape));
  };
  Bytes cut = testing::EthernetFrame(good);
  const auto wire_length = static_cast<std::uint32_t>(cut.size());
  cut.resize(60);
  const Bytes image = testing::PcapImage(
      1, {{0, 0, testing::EthernetFrame(Bytes(28, 0), 0x0806)},  // ARP
          {0, 0, testing::EthernetFrame(Bytes(40, 0x60), 0x86DD)},  // IPv6
          {0, 0, packet(tcp)},
          {0, 0, packet(more_fragments)},
          {0, 0, packet(later_fragment)},
          {0, 0, packet(bad_ihl)},
          {0, 0, packet(long_udp)},
          {0, 0, packet(short_udp)},
          {0, 0, Bytes(10, 0xAB)},  // shorter than an Ethernet header
          {0, 0, cut, wire_length},
          {0, 0, testing::EthernetFrame(good)}});
  PcapReader reader = OpenOrDie(image);
  int datagrams = 0;
  while (reader.Next()) ++datagrams;
  const CaptureStats& stats = reader.stats();
  EXPECT_EQ(datagrams, 1);
  EXPECT_EQ(stats.frames, 11u);
  EXPECT_EQ(stats.udp_datagrams, 1u);
  EXPECT_EQ(stats.non_udp, 3u);
  EXPECT_EQ(stats.fragments, 2u);
  EXPECT_EQ(stats.malformed, 4u);
  EXPECT_EQ(stats.truncated_frames, 1u);
  EXPECT_FALSE(stats.file_truncated);
}

TEST(PcapReader, ToleratesTheVelodyneIpv4TotalLengthQuirkButNoOtherOverrun) {
  // Early VLP-16 position packets: IPv4 says 1234 bytes, the frame and UDP say 520.
  testing::Ipv4Shape quirk;
  quirk.ipv4_total_length_delta = 1234 - (20 + 8 + 512);
  testing::Ipv4Shape quirk_with_long_udp = quirk;
  quirk_with_long_udp.udp_length_delta = 700;
  const Bytes position = testing::CountingPayload(512);
  const Ipv4Endpoint position_port{0xFFFFFFFF, 8308};
  PcapReader reader = OpenOrDie(testing::PcapImage(
      1, {{0, 0, testing::EthernetFrame(testing::Ipv4Udp(kSensor, position_port, position, quirk))},
          {0, 0, testing::EthernetFrame(
                     testing::Ipv4Udp(kSensor, position_port, position, quirk_with_long_udp))}}));
  const std::optional<UdpDatagram> datagram = reader.Next();
  ASSERT_TRUE(datagram.has_value());
  EXPECT_EQ(datagram->destination.port, 8308);
  EXPECT_EQ(testing::PayloadOf(*datagram), position);
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_EQ(reader.stats().udp_datagrams, 1u);
  EXPECT_EQ(reader.stats().ipv4_length_overruns, 1u);
  EXPECT_EQ(reader.stats().malformed, 1u);
}

TEST(PcapReader, AcceptsEthernetPaddingAfterTheIpPacket) {
  Bytes frame = testing::EthernetFrame(SensorPacket(4));  // 46 bytes
  frame.resize(60, 0);                                    // minimum Ethernet frame
  PcapReader reader = OpenOrDie(testing::PcapImage(1, {{0, 0, frame}}));
  const std::optional<UdpDatagram> datagram = reader.Next();
  ASSERT_TRUE(datagram.has_value());
  EXPECT_EQ(testing::PayloadOf(*datagram), testing::CountingPayload(4));
}

TEST(PcapReader, RefusesUnsupportedLinkTypeByName) {
  const Result<PcapReader> reader = PcapReader::OpenMemory(testing::PcapImage(105, {}));
  ASSERT_FALSE(reader.ok());
  EXPECT_NE(reader.error().message.find("unsupported link type IEEE802_11 (105)"),
            std::string::npos)
      << reader.error().message;
}

TEST(PcapReader, RefusesBytesThatAreNoCapture) {
  EXPECT_FALSE(PcapReader::OpenMemory(Bytes{}).ok());
  const Result<PcapReader> reader = PcapReader::OpenMemory(Bytes(100, 0x42));
  ASSERT_FALSE(reader.ok());
  EXPECT_NE(reader.error().message.find("in-memory capture"), std::string::npos);
}

TEST(PcapReader, NamesTheFileItCannotOpen) {
  const Result<PcapReader> reader = PcapReader::Open("/nonexistent/flat2d/capture.pcap");
  ASSERT_FALSE(reader.ok());
  EXPECT_NE(reader.error().message.find("/nonexistent/flat2d/capture.pcap"), std::string::npos);
}

TEST(PcapReader, ReadsFromAFileAndDescribesIt) {
  const auto path = testing::WriteTempFile(
      "reader_file.pcap", testing::PcapImage(113, {{5, 6, testing::SllFrame(SensorPacket())}}));
  Result<PcapReader> reader = PcapReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_EQ(reader->link_type(), 113);
  EXPECT_NE(reader->Describe().find("LINUX_SLL"), std::string::npos) << reader->Describe();
  EXPECT_TRUE(reader->Next().has_value());
}

}  // namespace
}  // namespace flat2d::hal::net
