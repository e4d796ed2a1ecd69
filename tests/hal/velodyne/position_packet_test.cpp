#include "hal/velodyne/position_packet.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/velodyne/sensor_clock.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr const char* kRmc =
    "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E";

// A position packet built byte by byte as VLP-16 manual Table 9-3 lays it out.
std::vector<std::uint8_t> MakePacket(std::uint32_t us_past_hour, std::uint8_t pps,
                                     const std::string& sentence) {
  std::vector<std::uint8_t> bytes(512, 0);
  bytes[198] = static_cast<std::uint8_t>(us_past_hour);
  bytes[199] = static_cast<std::uint8_t>(us_past_hour >> 8);
  bytes[200] = static_cast<std::uint8_t>(us_past_hour >> 16);
  bytes[201] = static_cast<std::uint8_t>(us_past_hour >> 24);
  bytes[202] = pps;
  for (std::size_t i = 0; i < sentence.size(); ++i) {
    bytes[206 + i] = static_cast<std::uint8_t>(sentence[i]);
  }
  return bytes;
}

TEST(PositionPacket, DecodesTimestampPpsAndRmc) {
  // 18 min 2.342001 s past the hour, bytes 71 3A 83 40 as in the MRPT capture.
  const auto bytes = MakePacket(0x40833A71, 2, std::string(kRmc) + "\r\n");
  EXPECT_EQ(bytes[198], 0x71);
  const auto packet = DecodePositionPacket(bytes);
  ASSERT_TRUE(packet.ok()) << packet.error().message;
  EXPECT_EQ(packet->us_past_hour, 1'082'342'001u);
  EXPECT_EQ(packet->pps_status, PpsStatus::kLocked);
  EXPECT_EQ(PpsStatusName(packet->pps_status), "locked");
  EXPECT_EQ(packet->nmea_sentence(), kRmc);
  ASSERT_TRUE(packet->rmc.has_value());
  EXPECT_TRUE(packet->rmc->valid);
  EXPECT_EQ(packet->rmc->utc_time_ns, 1'453'364'282 * kNsPerSecond);
  EXPECT_NEAR(packet->rmc->latitude_deg, 36.829130930, 1e-9);
  EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), packet->raw.begin()));
}

TEST(PositionPacket, EveryPpsValueOfTheManualDecodes) {
  const PpsStatus expected[] = {PpsStatus::kAbsent, PpsStatus::kSynchronizing,
                                PpsStatus::kLocked, PpsStatus::kError};
  for (std::uint8_t value = 0; value < 4; ++value) {
    const auto packet = DecodePositionPacket(MakePacket(0, value, ""));
    ASSERT_TRUE(packet.ok()) << packet.error().message;
    EXPECT_EQ(packet->pps_status, expected[value]);
  }
}

TEST(PositionPacket, NoGpsAttachedIsNotAnError) {
  const auto packet = DecodePositionPacket(MakePacket(3'599'999'999u, 0, ""));
  ASSERT_TRUE(packet.ok()) << packet.error().message;
  EXPECT_EQ(packet->us_past_hour, 3'599'999'999u);
  EXPECT_TRUE(packet->nmea_sentence().empty());
  EXPECT_FALSE(packet->rmc.has_value());
}

TEST(PositionPacket, NonRmcSentenceIsKeptWithoutFix) {
  const std::string gga = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
  const auto packet = DecodePositionPacket(MakePacket(0, 2, gga + "\r\n"));
  ASSERT_TRUE(packet.ok()) << packet.error().message;
  EXPECT_EQ(packet->nmea_sentence(), gga);
  EXPECT_FALSE(packet->rmc.has_value());
}

TEST(PositionPacket, SentenceEndedByNulOrBareLfDecodes) {
  for (const std::string& ending : {std::string(), std::string("\n"), std::string("\r")}) {
    const auto packet = DecodePositionPacket(MakePacket(0, 2, kRmc + ending));
    ASSERT_TRUE(packet.ok()) << packet.error().message;
    EXPECT_EQ(packet->nmea_sentence(), kRmc);
  }
}

struct BadPacket {
  std::vector<std::uint8_t> bytes;
  const char* in_message;
};

TEST(PositionPacket, RejectsWrongSizeAndGarbage) {
  std::string bad_checksum = kRmc;
  bad_checksum.back() = 'F';  // *2F instead of *2E
  auto no_terminator = MakePacket(0, 2, "");
  std::fill(no_terminator.begin() + 206, no_terminator.end(), 'A');
  no_terminator[206] = '$';
  auto non_ascii = MakePacket(0, 2, std::string(kRmc) + "\r\n");
  non_ascii[220] = 0xC3;
  const BadPacket cases[] = {
      {MakePacket(0, 2, bad_checksum + "\r\n"), "checksum"},
      {std::vector<std::uint8_t>(511, 0), "511 bytes"},
      {std::vector<std::uint8_t>(1206, 0), "1206 bytes"},
      {{}, "0 bytes"},
      {MakePacket(3'600'000'000u, 2, ""), "offset 198"},
      {MakePacket(0, 4, ""), "PPS status 4"},
      {no_terminator, "terminator"},
      {non_ascii, "offset 220"},
      {MakePacket(0, 2, "GPRMC,1\r\n"), "'$'"},
  };
  for (const BadPacket& bad : cases) {
    const auto packet = DecodePositionPacket(bad.bytes);
    ASSERT_FALSE(packet.ok()) << "accepted a packet expected to fail with " << bad.in_message;
    EXPECT_NE(packet.error().message.find(bad.in_message), std::string::npos)
        << packet.error().message;
  }
}

TEST(PositionPacket, RandomBytesNeverCrash) {
  constexpr unsigned kSeed = 42;
  std::mt19937 random(kSeed);
  std::uniform_int_distribution<int> byte(0, 255);
  int decoded = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    auto bytes = MakePacket(static_cast<std::uint32_t>(random() % 3'600'000'000u),
                            static_cast<std::uint8_t>(random() % 4), kRmc);
    // Corrupt a few bytes of the sentence region, sometimes the terminator.
    for (int k = 0; k < 3; ++k) {
      bytes[206 + random() % 100] = static_cast<std::uint8_t>(byte(random));
    }
    decoded += DecodePositionPacket(bytes).ok() ? 1 : 0;
  }
  // Most corruptions hit the checksummed sentence; nothing crashed (ASan/UBSan builds).
  EXPECT_LT(decoded, 2000) << "seed " << kSeed;
}

// The UDP payloads of `size` bytes in a classic little-endian Ethernet pcap: 24-byte global
// header, 16-byte record headers, 42 bytes of Ethernet + IPv4 + UDP before each payload.
std::vector<std::vector<std::uint8_t>> PayloadsOfSize(const std::filesystem::path& path,
                                                      std::size_t size) {
  std::ifstream file(path, std::ios::binary);
  const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(file)), {});
  std::vector<std::vector<std::uint8_t>> payloads;
  std::size_t offset = 24;
  while (offset + 16 <= data.size()) {
    const std::uint32_t captured = ReadU32(data.data() + offset + 8);
    offset += 16;
    if (offset + captured > data.size()) break;
    if (captured == 42 + size) {
      payloads.emplace_back(data.begin() + static_cast<std::ptrdiff_t>(offset + 42),
                            data.begin() + static_cast<std::ptrdiff_t>(offset + captured));
    }
    offset += captured;
  }
  return payloads;
}

TEST(PositionPacket, FirstPacketOfTheMrptVlp16CaptureHasAFixOf2016_01_21) {
  FLAT2D_REQUIRE_DATA(pcap, "velodyne/vlp16/mrpt_sample_velodyne_vlp16_gps.pcap");
  const auto payloads = PayloadsOfSize(pcap, 512);
  ASSERT_EQ(payloads.size(), 57u) << pcap;  // PROVENANCE.md: 57 position packets
  const auto packet = DecodePositionPacket(payloads.front());
  ASSERT_TRUE(packet.ok()) << packet.error().message;
  ASSERT_TRUE(packet->rmc.has_value()) << packet->nmea_sentence();
  EXPECT_EQ(packet->rmc->status, 'A');
  EXPECT_TRUE(packet->rmc->valid);
  // 2016-01-21 is day 46 * 365 + 11 + 20 = 16821 of the Unix epoch.
  EXPECT_EQ(packet->rmc->utc_time_ns / kNsPerDay, 16821);
  EXPECT_EQ(packet->rmc->utc_time_ns % kNsPerDay, (8 * 3600 + 18 * 60 + 2) * kNsPerSecond);
  EXPECT_EQ(packet->pps_status, PpsStatus::kLocked);
  EXPECT_EQ(packet->us_past_hour, 1'082'342'001u);  // 18 min 2.342001 s
}

TEST(PositionPacket, Hdl32eCapturePacketsDecodeWithGyroBytesAndFeedTheClock) {
  FLAT2D_REQUIRE_DATA(pcap, "velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap");
  const auto payloads = PayloadsOfSize(pcap, 512);
  ASSERT_EQ(payloads.size(), 100u) << pcap;
  SensorClock clock;
  for (const auto& payload : payloads) {
    const auto packet = DecodePositionPacket(payload);
    ASSERT_TRUE(packet.ok()) << packet.error().message;
    ASSERT_TRUE(packet->rmc.has_value()) << packet->nmea_sentence();
    // HDL-32E: no PPS byte (reads 0); gyro/temperature/accelerometer words in bytes 14-37.
    EXPECT_EQ(packet->pps_status, PpsStatus::kAbsent);
    EXPECT_TRUE(std::any_of(packet->raw.begin() + 14, packet->raw.begin() + 38,
                            [](std::uint8_t byte) { return byte != 0; }));
    clock.ObservePositionPacket(*packet);
  }
  EXPECT_EQ(clock.stats().gps_fixes_accepted, 100u);
  EXPECT_EQ(clock.stats().gps_fixes_rejected, 0u);
  const auto first = DecodePositionPacket(payloads.front());
  ASSERT_TRUE(first.ok());
  // $GPRMC,220243,A,...,111212,...,D: 2012-12-11 is day 42 * 365 + 10 + 335 + 10 = 15685.
  EXPECT_EQ(first->rmc->utc_time_ns, 15685 * kNsPerDay + (22 * 3600 + 2 * 60 + 43) * kNsPerSecond);
  EXPECT_EQ(first->rmc->mode, 'D');
  EXPECT_NEAR(first->rmc->speed_mps, 28.8 * 1852.0 / 3600.0, 1e-12);
  // The packet's own time, 2 min 44.475540 s past the hour, falls in the fix's hour.
  EXPECT_EQ(first->us_past_hour, 164'475'540u);
  SensorClock fresh;
  fresh.ObservePositionPacket(*first);
  EXPECT_EQ(fresh.Resolve(first->us_past_hour, 0),
            15685 * kNsPerDay + 22 * kNsPerHour + 164'475'540 * kNsPerUs);
}

TEST(PositionPacket, Vlp16CaptureWithoutGpsHasNoSentence) {
  FLAT2D_REQUIRE_DATA(pcap, "velodyne/vlp16/rust-lidar-utils_velodyne_vlp16_prod0x21.pcap");
  const auto payloads = PayloadsOfSize(pcap, 512);
  ASSERT_EQ(payloads.size(), 16u) << pcap;
  for (const auto& payload : payloads) {
    const auto packet = DecodePositionPacket(payload);
    ASSERT_TRUE(packet.ok()) << packet.error().message;
    EXPECT_TRUE(packet->nmea_sentence().empty());
    EXPECT_FALSE(packet->rmc.has_value());
  }
}

}  // namespace
}  // namespace flat2d::hal::velodyne
