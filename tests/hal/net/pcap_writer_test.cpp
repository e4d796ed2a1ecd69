// PcapWriter -> PcapReader round trips and the bytes of the frames the writer makes.
#include "hal/net/pcap_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <random>

#include "hal/net/pcap_reader.hpp"
#include "tests/hal/net/capture_images.hpp"

namespace flat2d::hal::net {
namespace {

using testing::Bytes;

struct OwnedDatagram {
  TimeNs receive_time_ns = 0;
  Ipv4Endpoint source;
  Ipv4Endpoint destination;
  Bytes payload;
  UdpDatagram View() const { return {receive_time_ns, source, destination, payload}; }
};

std::vector<OwnedDatagram> RandomDatagrams(std::uint32_t seed, int count) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<std::uint32_t> address;
  std::uniform_int_distribution<int> port(0, 65535);
  std::uniform_int_distribution<std::size_t> size(0, 1500);
  std::uniform_int_distribution<int> byte(0, 255);
  const std::uint32_t special_destinations[] = {0xFFFFFFFF, 0xEFFF0001, 0x7F000001};
  std::vector<OwnedDatagram> datagrams;
  TimeNs time_ns = 1'700'000'000LL * kNsPerSecond + 123;
  for (int i = 0; i < count; ++i) {
    OwnedDatagram datagram;
    time_ns += std::uniform_int_distribution<TimeNs>(0, 3 * kNsPerSecond)(random);
    datagram.receive_time_ns = time_ns;
    datagram.source = {address(random), static_cast<std::uint16_t>(port(random))};
    datagram.destination = {i < 3 ? special_destinations[i] : address(random),
                            static_cast<std::uint16_t>(port(random))};
    datagram.payload.resize(i == 3 ? kMaxUdpPayloadBytes : size(random));
    for (std::uint8_t& value : datagram.payload) value = static_cast<std::uint8_t>(byte(random));
    datagrams.push_back(std::move(datagram));
  }
  return datagrams;
}

void WriteAll(const std::filesystem::path& path, const std::vector<OwnedDatagram>& datagrams,
              TimestampPrecision precision) {
  Result<PcapWriter> writer = PcapWriter::Create(path, {precision});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  for (const OwnedDatagram& datagram : datagrams) {
    const Status written = writer->Write(datagram.View());
    ASSERT_TRUE(written.ok()) << written.error().message;
  }
  EXPECT_EQ(writer->frames_written(), datagrams.size());
  const Status closed = writer->Close();
  ASSERT_TRUE(closed.ok()) << closed.error().message;
}

void ExpectReadBack(const std::filesystem::path& path, const std::vector<OwnedDatagram>& expected,
                    TimeNs time_resolution_ns) {
  Result<PcapReader> reader = PcapReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE("datagram " + std::to_string(i));
    const std::optional<UdpDatagram> datagram = reader->Next();
    ASSERT_TRUE(datagram.has_value());
    const TimeNs expected_time =
        expected[i].receive_time_ns / time_resolution_ns * time_resolution_ns;
    EXPECT_EQ(datagram->receive_time_ns, expected_time);
    EXPECT_EQ(datagram->source.address, expected[i].source.address);
    EXPECT_EQ(datagram->source.port, expected[i].source.port);
    EXPECT_EQ(datagram->destination.address, expected[i].destination.address);
    EXPECT_EQ(datagram->destination.port, expected[i].destination.port);
    EXPECT_EQ(testing::PayloadOf(*datagram), expected[i].payload);
  }
  EXPECT_FALSE(reader->Next().has_value());
  EXPECT_EQ(reader->stats().frames, expected.size());
  EXPECT_FALSE(reader->stats().file_truncated);
}

Bytes ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(PcapWriter, RoundTripsNanosecondCapturesExactly) {
  constexpr std::uint32_t kSeed = 42;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const auto datagrams = RandomDatagrams(kSeed, 60);
  const auto path = testing::TempPath("writer_ns.pcap");
  WriteAll(path, datagrams, TimestampPrecision::kNanosecond);
  ExpectReadBack(path, datagrams, 1);
  EXPECT_EQ(ReadFile(path).at(0), 0x4D);  // a1b23c4d in host (little-endian) order
}

TEST(PcapWriter, RoundTripsMicrosecondCapturesToTheMicrosecond) {
  constexpr std::uint32_t kSeed = 7;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const auto datagrams = RandomDatagrams(kSeed, 20);
  const auto path = testing::TempPath("writer_us.pcap");
  WriteAll(path, datagrams, TimestampPrecision::kMicrosecond);
  ExpectReadBack(path, datagrams, kNsPerUs);
  EXPECT_EQ(ReadFile(path).at(0), 0xD4);  // a1b2c3d4 in host (little-endian) order
}

TEST(PcapWriter, WritesValidIpv4HeaderChecksumsAndStandardMacs) {
  const auto path = testing::TempPath("writer_bytes.pcap");
  const Bytes payload = testing::CountingPayload(1206);
  OwnedDatagram datagram{5 * kNsPerSecond, {0xC0A801C9, 2368}, {0xFFFFFFFF, 2368}, payload};
  WriteAll(path, {datagram}, TimestampPrecision::kNanosecond);
  const Bytes file = ReadFile(path);
  constexpr std::size_t kFrame = 24 + 16;  // global header + record header
  ASSERT_EQ(file.size(), kFrame + 14 + 20 + 8 + payload.size());
  EXPECT_EQ(Bytes(file.begin() + kFrame, file.begin() + kFrame + 6), Bytes(6, 0xFF));
  std::uint32_t sum = 0;  // a valid header sums to 0xFFFF in one's complement
  for (std::size_t i = 0; i < 20; i += 2) {
    sum += (file[kFrame + 14 + i] << 8) | file[kFrame + 14 + i + 1];
  }
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  EXPECT_EQ(sum, 0xFFFFu);
}

TEST(PcapWriter, RefusesOversizePayloadsNegativeTimesAndWritesAfterClose) {
  const auto path = testing::TempPath("writer_errors.pcap");
  Result<PcapWriter> writer = PcapWriter::Create(path);
  ASSERT_TRUE(writer.ok());
  const Bytes huge(kMaxUdpPayloadBytes + 1);
  EXPECT_FALSE(writer->Write({0, {}, {}, huge}).ok());
  EXPECT_FALSE(writer->Write({-1, {}, {}, {}}).ok());
  EXPECT_TRUE(writer->Write({0, {}, {}, {}}).ok());  // an empty payload is fine
  EXPECT_TRUE(writer->Close().ok());
  EXPECT_FALSE(writer->Write({0, {}, {}, {}}).ok());
}

TEST(PcapWriter, NamesTheFileItCannotCreate) {
  const Result<PcapWriter> writer = PcapWriter::Create("/nonexistent/flat2d/out.pcap");
  ASSERT_FALSE(writer.ok());
  EXPECT_NE(writer.error().message.find("/nonexistent/flat2d/out.pcap"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::hal::net
