// The position packet encoder against DecodePositionPacket / ParseRmc, and byte for byte
// against the position packets of real captures.
#include "hal/velodyne/position_packet_encoder.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>
#include <random>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hal/net/datagram_source.hpp"
#include "tests/testing/allocation_counter.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr double kKnotsToMps = 1852.0 / 3600.0;
constexpr std::string_view kMrptRmc =
    "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E";
constexpr std::string_view kHdl32eRmc =
    "$GPRMC,220243,A,3708.5809,N,12139.7813,W,028.8,158.3,111212,013.8,E,D*03";

RmcFormat Hdl32eGarminFormat() {
  RmcFormat format;
  format.time_decimals = 0;
  format.minute_decimals = 4;
  format.speed_decimals = 1;
  format.speed_digits = 3;
  format.variation_digits = 3;
  format.course_digits = 3;
  return format;
}

std::string_view Sentence(const PositionPacketBytes& bytes) {
  const auto* begin = reinterpret_cast<const char*>(bytes.data()) + kPositionNmeaOffset;
  return {begin, static_cast<std::size_t>(std::find(begin, begin + 306, '\0') - begin)};
}

// Real sentences re-emitted from their parsed fix, character for character.
TEST(PositionPacketEncoder, ReproducesRealSentences) {
  struct Case {
    std::string_view sentence;
    RmcFormat format;
  };
  for (const Case& c : {Case{kMrptRmc, RmcFormat{}}, Case{kHdl32eRmc, Hdl32eGarminFormat()}}) {
    const auto fix = ParseRmc(c.sentence);
    ASSERT_TRUE(fix.ok()) << fix.error().message;
    const auto bytes = EncodePositionPacket({0x40833A71, PpsStatus::kLocked, *fix, c.format});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    EXPECT_EQ(Sentence(*bytes), std::string(c.sentence) + "\r\n");
    EXPECT_EQ((*bytes)[198], 0x71);
    EXPECT_EQ((*bytes)[201], 0x40);
    EXPECT_EQ((*bytes)[202], 2);
  }
}

RmcFix RandomFix(std::mt19937& rng) {
  std::uniform_int_distribution<std::int64_t> seconds(315'532'800, 3'471'292'799);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RmcFix fix;
  fix.has_time = true;
  fix.utc_time_ns = seconds(rng) * kNsPerSecond + std::uniform_int_distribution<int>(0, 99)(rng) *
                                                      10 * kNsPerMs;
  fix.status = unit(rng) < 0.8 ? 'A' : 'V';
  fix.has_position = true;
  fix.latitude_deg = -90.0 + 180.0 * unit(rng);
  fix.longitude_deg = -180.0 + 360.0 * unit(rng);
  fix.speed_mps = 60.0 * unit(rng);
  fix.course_deg = 360.0 * unit(rng);
  if (unit(rng) < 0.5) fix.magnetic_variation_deg = -30.0 + 60.0 * unit(rng);
  fix.mode = unit(rng) < 0.5 ? 'A' : (unit(rng) < 0.5 ? 'N' : '\0');
  return fix;
}

// (c) Encode -> DecodePositionPacket gives back every field, to the written precision.
TEST(PositionPacketEncoder, RoundTripsThroughTheDecoder) {
  constexpr unsigned kSeed = 42;
  std::mt19937 rng(kSeed);
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const RmcFormat format;  // 7 decimals of minutes, 3 of knots, 1 of degrees
  for (int i = 0; i < 500; ++i) {
    const RmcFix fix = RandomFix(rng);
    const auto us = std::uniform_int_distribution<std::uint32_t>(0, 3'599'999'999u)(rng);
    const auto pps = static_cast<PpsStatus>(i % 4);
    const auto bytes = EncodePositionPacket({us, pps, fix, format});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const auto packet = DecodePositionPacket(*bytes);
    ASSERT_TRUE(packet.ok()) << packet.error().message << " in " << Sentence(*bytes);
    SCOPED_TRACE(std::string(packet->nmea_sentence()));
    EXPECT_EQ(packet->us_past_hour, us);
    EXPECT_EQ(packet->pps_status, pps);
    ASSERT_TRUE(packet->rmc.has_value());
    const RmcFix& got = *packet->rmc;
    EXPECT_EQ(got.utc_time_ns, fix.utc_time_ns);  // whole centiseconds: exact
    EXPECT_EQ(got.status, fix.status);
    EXPECT_EQ(got.mode, fix.mode);
    EXPECT_EQ(got.valid, fix.status == 'A' && fix.mode != 'N');
    EXPECT_NEAR(got.latitude_deg, fix.latitude_deg, 0.5e-7 / 60 + 1e-12);
    EXPECT_NEAR(got.longitude_deg, fix.longitude_deg, 0.5e-7 / 60 + 1e-12);
    EXPECT_NEAR(got.speed_mps, fix.speed_mps, 0.5e-3 * kKnotsToMps + 1e-12);
    EXPECT_NEAR(got.course_deg, fix.course_deg, 0.05 + 1e-12);
    ASSERT_EQ(got.magnetic_variation_deg.has_value(), fix.magnetic_variation_deg.has_value());
    if (fix.magnetic_variation_deg) {
      EXPECT_NEAR(*got.magnetic_variation_deg, *fix.magnetic_variation_deg, 0.05 + 1e-12);
    }
  }
}

TEST(PositionPacketEncoder, EncodingAllocatesNothing) {
  const auto fix = ParseRmc(kMrptRmc);
  ASSERT_TRUE(fix.ok());
  const PositionPacketContent content{1, PpsStatus::kLocked, *fix, RmcFormat{}};
  const std::uint64_t before = testing::AllocationCount();
  const auto bytes = EncodePositionPacket(content);
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_TRUE(bytes.ok());
}

TEST(PositionPacketEncoder, TruncatesTimeAndCarriesRoundedMinutes) {
  RmcFix fix;
  fix.status = 'A';
  fix.has_time = true;
  fix.has_position = true;
  // 2079-12-31 23:59:59.999999999: truncated, not rounded into 2080.
  fix.utc_time_ns = 3'471'292'799 * kNsPerSecond + 999'999'999;
  fix.latitude_deg = 36.99999999;   // 59.9999994 minutes: rounds to 37 degrees
  fix.longitude_deg = -0.0000001;   // west of Greenwich by a hair
  RmcFormat format;
  format.minute_decimals = 4;
  const auto bytes = EncodePositionPacket({0, PpsStatus::kAbsent, fix, format});
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const std::string_view sentence = Sentence(*bytes);
  EXPECT_TRUE(sentence.starts_with(
      "$GPRMC,235959.99,A,3700.0000,N,00000.0000,W,0.000,0.0,311279,,"))
      << sentence;
  EXPECT_TRUE(ParseRmc(sentence).ok());
}

TEST(PositionPacketEncoder, VoidFixWithoutTimeOrPositionAndNoGps) {
  RmcFix fix;  // status 'V', nothing known
  const auto bytes = EncodePositionPacket({5, PpsStatus::kSynchronizing, fix, RmcFormat{}});
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const auto packet = DecodePositionPacket(*bytes);
  ASSERT_TRUE(packet.ok()) << packet.error().message;
  ASSERT_TRUE(packet->rmc.has_value()) << packet->nmea_sentence();
  EXPECT_FALSE(packet->rmc->has_time);
  EXPECT_FALSE(packet->rmc->has_position);
  EXPECT_FALSE(packet->rmc->valid);

  const auto no_gps = EncodePositionPacket({5, PpsStatus::kAbsent, std::nullopt, RmcFormat{}});
  ASSERT_TRUE(no_gps.ok());
  EXPECT_TRUE(std::all_of(no_gps->begin() + kPositionNmeaOffset, no_gps->end(),
                          [](std::uint8_t b) { return b == 0; }));
  const auto decoded = DecodePositionPacket(*no_gps);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->nmea_length, 0);
  EXPECT_FALSE(decoded->rmc.has_value());
}

TEST(PositionPacketEncoder, RejectsWhatTheDecoderWouldReject) {
  const auto fix = ParseRmc(kMrptRmc);
  ASSERT_TRUE(fix.ok());
  const auto encode = [](RmcFix f, std::uint32_t us = 0) {
    return EncodePositionPacket({us, PpsStatus::kLocked, f, RmcFormat{}}).ok();
  };
  EXPECT_TRUE(encode(*fix));
  EXPECT_FALSE(encode(*fix, 3'600'000'000u));
  RmcFix f = *fix;
  f.has_time = false;
  EXPECT_FALSE(encode(f));  // an active fix needs time and date
  f = *fix;
  f.latitude_deg = 90.5;
  EXPECT_FALSE(encode(f));
  f = *fix;
  f.utc_time_ns = 3'471'292'800 * kNsPerSecond;  // 2080-01-01 would read back as 1980
  EXPECT_FALSE(encode(f));
  f = *fix;
  f.course_deg = -1.0;
  EXPECT_FALSE(encode(f));
  f = *fix;
  f.mode = 'X';
  EXPECT_FALSE(encode(f));
  f = *fix;
  f.status = 'Q';
  EXPECT_FALSE(encode(f));
  EXPECT_FALSE(EncodePositionPacket({0, static_cast<PpsStatus>(4), std::nullopt, {}}).ok());
}

struct RealPositionCapture {
  const char* path;
  RmcFormat format;
  bool whole_packet;  // false: the sensor fills bytes outside the documented fields
  std::uint64_t position_packets;
};

void PrintTo(const RealPositionCapture& capture, std::ostream* os) { *os << capture.path; }

class ReEncodePositionCapture : public ::testing::TestWithParam<RealPositionCapture> {};

// (c) Real position packets, decoded and re-encoded from their fields: the VLP-16's whole
// 512 bytes are reproduced; the HDL-32E also sends gyro/temperature/accelerometer words
// (bytes 14-37, HDL-32E manual Appendix B) that the encoder does not write, so for it only
// the documented fields (198-202 and the sentence from 206) are compared.
TEST_P(ReEncodePositionCapture, DocumentedFieldsAreByteIdentical) {
  const RealPositionCapture& capture = GetParam();
  FLAT2D_REQUIRE_DATA(path, std::string("velodyne/") + capture.path);
  auto source = net::OpenCapture(path);
  ASSERT_TRUE(source.ok()) << source.error().message;
  std::uint64_t packets = 0;
  while (const auto datagram = (*source)->Next()) {
    if (datagram->payload.size() != kPositionPacketSize) continue;
    const auto packet = DecodePositionPacket(datagram->payload);
    ASSERT_TRUE(packet.ok()) << packet.error().message;
    const auto bytes = EncodePositionPacket(
        {packet->us_past_hour, packet->pps_status, packet->rmc, capture.format});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const std::size_t from = capture.whole_packet ? 0 : kPositionTimestampOffset;
    for (std::size_t i = from; i < kPositionPacketSize; ++i) {
      const bool undocumented = i > kPositionPpsStatusOffset && i < kPositionNmeaOffset;
      if (!capture.whole_packet && undocumented) continue;
      ASSERT_EQ((*bytes)[i], datagram->payload[i])
          << "packet " << packets << " byte " << i << ", sentence " << packet->nmea_sentence();
    }
    ++packets;
  }
  EXPECT_EQ(packets, capture.position_packets);
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, ReEncodePositionCapture,
    ::testing::Values(
        RealPositionCapture{"vlp16/mrpt_sample_velodyne_vlp16_gps.pcap", RmcFormat{}, true, 57},
        RealPositionCapture{"hdl32e/rust-lidar-utils_hdl32_example.pcap", Hdl32eGarminFormat(),
                            false, 100}),
    [](const ::testing::TestParamInfo<RealPositionCapture>& param_info) {
      std::string name = std::filesystem::path(param_info.param.path).stem().string();
      std::replace_if(
          name.begin(), name.end(),
          [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
      return name;
    });

}  // namespace
}  // namespace flat2d::hal::velodyne
