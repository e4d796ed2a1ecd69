// Counts from the shared real captures, as listed in data/PROVENANCE.md (velodyne/).
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>

#include "hal/net/datagram_source.hpp"
#include "hal/net/pcap_reader.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::net {
namespace {

struct CaptureFacts {
  std::string relative_path;
  std::uint64_t data_packets;      // 1206 bytes to port 2368
  std::uint64_t position_packets;  // 512 bytes to port 8308
  std::uint32_t source_address;    // 0: not checked (raw dumps have none)
  // Position packets of early VLP-16 firmware claim the data packets' IPv4 length.
  std::uint64_t ipv4_length_overruns = 0;
};

std::ostream& operator<<(std::ostream& out, const CaptureFacts& facts) {
  return out << facts.relative_path;
}

struct Tally {
  std::uint64_t data = 0;
  std::uint64_t position = 0;
  std::uint64_t other = 0;
  std::uint64_t wrong_source = 0;
  std::uint64_t time_went_back = 0;
};

Tally CountVelodynePackets(DatagramSource& source, std::uint32_t expected_source) {
  Tally tally;
  TimeNs previous_ns = 0;
  while (const std::optional<UdpDatagram> datagram = source.Next()) {
    if (datagram->payload.size() == 1206 && datagram->destination.port == 2368) {
      ++tally.data;
    } else if (datagram->payload.size() == 512 && datagram->destination.port == 8308) {
      ++tally.position;
    } else {
      ++tally.other;
    }
    if (expected_source != 0 && datagram->source.address != expected_source) ++tally.wrong_source;
    if (datagram->receive_time_ns < previous_ns) ++tally.time_went_back;
    previous_ns = datagram->receive_time_ns;
  }
  return tally;
}

class RealCapture : public ::testing::TestWithParam<CaptureFacts> {};

TEST_P(RealCapture, HasTheDocumentedPacketCounts) {
  const CaptureFacts& facts = GetParam();
  FLAT2D_REQUIRE_DATA(path, facts.relative_path);
  Result<std::unique_ptr<DatagramSource>> source = OpenCapture(path);
  ASSERT_TRUE(source.ok()) << source.error().message;
  const Tally tally = CountVelodynePackets(**source, facts.source_address);
  const CaptureStats& stats = (*source)->stats();
  EXPECT_EQ(tally.data, facts.data_packets);
  EXPECT_EQ(tally.position, facts.position_packets);
  EXPECT_EQ(tally.other, 0u);
  EXPECT_EQ(tally.wrong_source, 0u);
  EXPECT_EQ(tally.time_went_back, 0u);
  EXPECT_EQ(stats.frames, facts.data_packets + facts.position_packets);
  EXPECT_EQ(stats.non_udp + stats.fragments + stats.malformed + stats.truncated_frames, 0u);
  EXPECT_EQ(stats.ipv4_length_overruns, facts.ipv4_length_overruns);
  EXPECT_FALSE(stats.file_truncated) << stats.file_error;
}

constexpr std::uint32_t kNoSource = 0;
INSTANTIATE_TEST_SUITE_P(
    Velodyne, RealCapture,
    ::testing::Values(
        CaptureFacts{"velodyne/vlp16/mrpt_sample_velodyne_vlp16_gps.pcap", 293, 57, 0x0A000064},
        CaptureFacts{"velodyne/vlp16/rust-lidar-utils_velodyne_vlp16_prod0x21.pcap", 84, 16,
                     0xC0A801C8, 16},
        CaptureFacts{"velodyne/vlp16/rust-lidar-utils_velodyne_example.pcap", 84, 0, 0xC0A801C8},
        CaptureFacts{"velodyne/vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap", 603, 0,
                     0xC0A801C9},
        CaptureFacts{"velodyne/hdl32e/mrpt_sample_velodyne_hdl32.pcap", 500, 0, 0xC0A811A2},
        CaptureFacts{"velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap", 876, 100, 0xC0A801C9},
        CaptureFacts{"velodyne/hdl32e/rust-lidar-utils_velodyne_vlp32_is_hdl32e.pcap", 91, 9,
                     0xC0A801C9},
        CaptureFacts{"velodyne/vlp32c/DERIVED_nebula_vlp32c_1713492677464078412.pcap", 379, 0, 0},
        CaptureFacts{"velodyne/vls128/DERIVED_nebula_vls128_1614315746471294674.pcap", 2193, 0, 0},
        CaptureFacts{"velodyne/raw_payloads/einride_vlp16-go_testdata_recording.bin", 1000, 0,
                     kNoSource},
        CaptureFacts{"velodyne/raw_payloads/floriantimm_vlp16_dual_300rpm_C++_0.bin", 1500, 0,
                     kNoSource},
        CaptureFacts{"velodyne/raw_payloads/floriantimm_vlp16_last_300rpm_C++_Debug_0.bin", 1500,
                     0, kNoSource}),
    [](const ::testing::TestParamInfo<CaptureFacts>& capture) {
      // gtest names allow only letters, digits and '_': derive one from the file name.
      std::string name = std::filesystem::path(capture.param.relative_path).stem().string();
      for (char& c : name) {
        if (std::isalnum(static_cast<unsigned char>(c)) == 0) c = '_';
      }
      return name;
    });

TEST(RealCapture, Vlp16GpsSampleHasDocumentedTimesAndEndpoints) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vlp16/mrpt_sample_velodyne_vlp16_gps.pcap");
  Result<PcapReader> reader = PcapReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_EQ(reader->link_type(), 1);
  const std::optional<UdpDatagram> first = reader->Next();
  ASSERT_TRUE(first.has_value());
  // PROVENANCE rounds to ms: 2016-01-21T08:18:02.709 UTC; the record says .708714.
  EXPECT_EQ(first->receive_time_ns, 1453364282'708714000);
  EXPECT_EQ(first->destination.address, 0xFFFFFFFFu);
  TimeNs last_ns = first->receive_time_ns;
  while (const std::optional<UdpDatagram> datagram = reader->Next()) {
    last_ns = datagram->receive_time_ns;
  }
  EXPECT_EQ(last_ns / kNsPerMs, 1453364283096);
}

}  // namespace
}  // namespace flat2d::hal::net
