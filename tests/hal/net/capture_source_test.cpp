// RawPayloadReader and OpenCapture's choice of reader.
#include <gtest/gtest.h>

#include "hal/net/datagram_source.hpp"
#include "hal/net/raw_payload_reader.hpp"
#include "tests/hal/net/capture_images.hpp"

namespace flat2d::hal::net {
namespace {

using testing::Bytes;

Bytes RawRecords(int count, std::size_t record_size, std::size_t trailing_bytes = 0) {
  Bytes bytes;
  for (int i = 0; i < count; ++i) {
    const Bytes record = testing::CountingPayload(record_size, static_cast<std::uint8_t>(i));
    bytes.insert(bytes.end(), record.begin(), record.end());
  }
  bytes.resize(bytes.size() + trailing_bytes, 0xEE);
  return bytes;
}

TEST(RawPayloadReader, ReadsBackToBackRecordsWithoutTimestamps) {
  const auto path = testing::WriteTempFile("raw_three.bin", RawRecords(3, 1206));
  Result<RawPayloadReader> reader = RawPayloadReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  for (int i = 0; i < 3; ++i) {
    const std::optional<UdpDatagram> datagram = reader->Next();
    ASSERT_TRUE(datagram.has_value());
    EXPECT_EQ(datagram->receive_time_ns, 0);
    EXPECT_EQ(datagram->destination.port, 2368);
    EXPECT_EQ(testing::PayloadOf(*datagram),
              testing::CountingPayload(1206, static_cast<std::uint8_t>(i)));
  }
  EXPECT_FALSE(reader->Next().has_value());
  EXPECT_EQ(reader->stats().udp_datagrams, 3u);
  EXPECT_EQ(reader->stats().truncated_frames, 0u);
  EXPECT_FALSE(reader->stats().file_truncated);
}

TEST(RawPayloadReader, CountsATrailingPartialRecordAsTruncated) {
  const auto path = testing::WriteTempFile("raw_partial.bin", RawRecords(2, 512, 100));
  RawPayloadOptions options;
  options.record_size = 512;
  options.destination = {0x7F000001, 8308};
  Result<RawPayloadReader> reader = RawPayloadReader::Open(path, options);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  int datagrams = 0;
  while (const std::optional<UdpDatagram> datagram = reader->Next()) {
    EXPECT_EQ(datagram->destination.port, 8308);
    EXPECT_EQ(datagram->payload.size(), 512u);
    ++datagrams;
  }
  EXPECT_EQ(datagrams, 2);
  EXPECT_EQ(reader->stats().frames, 3u);
  EXPECT_EQ(reader->stats().truncated_frames, 1u);
  EXPECT_TRUE(reader->stats().file_truncated);
  EXPECT_NE(reader->stats().file_error.find("100 bytes"), std::string::npos)
      << reader->stats().file_error;
}

TEST(RawPayloadReader, RefusesImpossibleRecordSizes) {
  const auto path = testing::WriteTempFile("raw_any.bin", RawRecords(1, 10));
  RawPayloadOptions options;
  options.record_size = 0;
  EXPECT_FALSE(RawPayloadReader::Open(path, options).ok());
  options.record_size = kMaxUdpPayloadBytes + 1;
  EXPECT_FALSE(RawPayloadReader::Open(path, options).ok());
}

TEST(OpenCapture, PicksPcapPcapngOrRawByContent) {
  const Bytes frame = testing::EthernetFrame(
      testing::Ipv4Udp({0x0A000064, 2368}, {0xFFFFFFFF, 2368}, testing::CountingPayload(1206)));
  struct Case {
    std::string name;
    Bytes bytes;
    std::string described_as;
  };
  const std::vector<Case> cases = {
      {"open_ns.pcap", testing::PcapImage(1, {{1, 2, frame}}, true), "pcap capture"},
      {"open_us.pcap", testing::PcapImage(1, {{1, 2, frame}}, false), "pcap capture"},
      {"open.pcapng", testing::PcapngImage(1, {{1, 2, frame}}), "pcap capture"},
      {"open_raw.bin", RawRecords(4, 1206), "raw payload dump"},
  };
  for (const Case& test_case : cases) {
    SCOPED_TRACE(test_case.name);
    const auto path = testing::WriteTempFile(test_case.name, test_case.bytes);
    Result<std::unique_ptr<DatagramSource>> source = OpenCapture(path);
    ASSERT_TRUE(source.ok()) << source.error().message;
    EXPECT_NE((*source)->Describe().find(test_case.described_as), std::string::npos)
        << (*source)->Describe();
    const std::optional<UdpDatagram> datagram = (*source)->Next();
    ASSERT_TRUE(datagram.has_value());
    EXPECT_EQ(datagram->payload.size(), 1206u);
  }
}

TEST(OpenCapture, ExplainsFilesItCannotRead) {
  const auto odd = testing::WriteTempFile("open_odd.bin", RawRecords(1, 1000));
  const Result<std::unique_ptr<DatagramSource>> odd_source = OpenCapture(odd);
  ASSERT_FALSE(odd_source.ok());
  EXPECT_NE(odd_source.error().message.find("not pcap or pcapng"), std::string::npos)
      << odd_source.error().message;
  EXPECT_NE(odd_source.error().message.find("1000 bytes"), std::string::npos);

  EXPECT_FALSE(OpenCapture(testing::WriteTempFile("open_empty.bin", {})).ok());
  EXPECT_FALSE(OpenCapture("/nonexistent/flat2d/capture.pcap").ok());

  // A pcap magic number with a broken header is a pcap error, not a raw dump.
  Bytes broken = testing::PcapImage(1, {});
  broken.resize(10);
  const Result<std::unique_ptr<DatagramSource>> broken_source =
      OpenCapture(testing::WriteTempFile("open_broken.pcap", broken), 10);
  ASSERT_FALSE(broken_source.ok());
  EXPECT_NE(broken_source.error().message.find("cannot open capture"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::hal::net
