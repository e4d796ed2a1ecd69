// The data packet encoder against the decoder (every model x return mode), against the
// test-only byte builder, and byte for byte against real captures.
#include "hal/velodyne/packet_encoder.hpp"
#include "hal/velodyne/firing_schedule.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <ostream>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/packet_decoder.hpp"
#include "tests/testing/allocation_counter.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr double kUnitsToRad = 2.0 * std::numbers::pi / 36000.0;
constexpr unsigned kEncoderSeed = 42;

// Random raw content: azimuths advance `step` units per firing from a random start (with
// the wrap at 36000 inside the packet for some seeds); about one record in five is empty.
DataPacketContent RandomContent(std::mt19937& rng, const FiringSchedule& schedule,
                                ReturnMode mode, std::uint8_t product_id) {
  DataPacketContent content;
  const int start = std::uniform_int_distribution<int>(0, 35999)(rng);
  const int step = std::uniform_int_distribution<int>(18, 40)(rng);
  std::uniform_int_distribution<int> raw(0, 65535), byte(0, 255), empty(0, 4);
  for (int block = 0; block < 12; ++block) {
    content.block_azimuth_units[static_cast<std::size_t>(block)] =
        static_cast<std::uint16_t>((start + schedule.FiringOfBlock(block) * step) % 36000);
    for (ChannelRecord& record : content.records[static_cast<std::size_t>(block)]) {
      record.distance_units = empty(rng) == 0 ? 0 : static_cast<std::uint16_t>(raw(rng));
      record.reflectivity = static_cast<std::uint8_t>(byte(rng));
    }
  }
  content.us_past_hour = std::uniform_int_distribution<std::uint32_t>(0, 3'599'999'999u)(rng);
  content.mode = mode;
  content.product_id = product_id;
  return content;
}

double AngleDiffUnits(double a_rad, double b_rad) {
  double diff = std::remainder(a_rad - b_rad, 2.0 * std::numbers::pi);
  return std::abs(diff) / kUnitsToRad;
}

using ModelMode = std::tuple<Model, ReturnMode>;
class EncodeDecode : public ::testing::TestWithParam<ModelMode> {};

// (a) Every record comes back from PacketDecoder where FiringSchedule says, with its range,
// intensity, interpolated azimuth (manuals 9.5) and firing time.
TEST_P(EncodeDecode, EveryRecordDecodesToItsContent) {
  const auto [model, mode] = GetParam();
  const LaserTable table = DefaultLaserTable(model);
  const FiringSchedule schedule(model, mode);
  PacketDecoder decoder(table);
  DecodedPacket decoded;
  std::mt19937 rng(kEncoderSeed);
  SCOPED_TRACE("seed " + std::to_string(kEncoderSeed));
  for (int trial = 0; trial < 20; ++trial) {
    const DataPacketContent content = RandomContent(rng, schedule, mode, 0x5A);
    const auto bytes = EncodeDataPacket(content);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    decoder.Decode(*bytes, decoded);
    ASSERT_EQ(decoded.error, PacketError::kNone) << PacketErrorName(decoded.error);
    EXPECT_EQ(decoded.us_past_hour, content.us_past_hour);
    EXPECT_EQ(decoded.return_mode, mode);
    EXPECT_EQ(decoded.product_id, 0x5A);
    ASSERT_EQ(decoded.num_fans, 12 * schedule.fans_per_block());
    const int block_step = mode == ReturnMode::kDual ? 2 : 1;
    const int gap = (content.block_azimuth_units[static_cast<std::size_t>(block_step)] -
                     content.block_azimuth_units[0] + 36000) % 36000;
    for (int block = 0; block < 12; ++block) {
      const double block_start_us = schedule.FiringOfBlock(block) * schedule.block_period_us();
      for (int c = 0; c < 32; ++c) {
        SCOPED_TRACE("trial " + std::to_string(trial) + " block " + std::to_string(block) +
                     " channel " + std::to_string(c));
        const ChannelFiring& firing = schedule.At(block, c);
        const Fan& fan = decoded.fans[static_cast<std::size_t>(firing.fan)];
        const LaserReturn& r = fan.returns[static_cast<std::size_t>(firing.laser_id)];
        const ChannelRecord& record =
            content.records[static_cast<std::size_t>(block)][static_cast<std::size_t>(c)];
        const LaserCorrection& laser = table.lasers[static_cast<std::size_t>(firing.laser_id)];
        EXPECT_EQ(fan.kind, schedule.KindOfBlock(block));
        EXPECT_EQ(r.intensity, record.reflectivity);
        const double range = record.distance_units == 0
                                 ? 0.0
                                 : record.distance_units * table.distance_resolution_m +
                                       laser.distance_offset_m;
        EXPECT_NEAR(r.range_m, range, 1e-6 * range + 1e-6);
        const double expected_units =
            content.block_azimuth_units[static_cast<std::size_t>(block)] +
            gap * (firing.time_offset_us - block_start_us) / schedule.block_period_us() -
            laser.rot_correction_rad / kUnitsToRad;
        EXPECT_LE(AngleDiffUnits(static_cast<double>(r.azimuth_rad), expected_units * kUnitsToRad), 1.01);
        EXPECT_NEAR(static_cast<double>(fan.stamp_ns + r.time_offset_ns),
                    firing.time_offset_us * 1e3, 1.0);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllModelsAndModes, EncodeDecode,
    ::testing::Combine(::testing::Values(Model::kVlp16, Model::kHdl32e, Model::kVlp32c),
                       ::testing::Values(ReturnMode::kStrongest, ReturnMode::kLast,
                                         ReturnMode::kDual)),
    [](const ::testing::TestParamInfo<ModelMode>& param_info) {
      std::string name = std::string(ModelName(std::get<0>(param_info.param))) + "_" +
                         std::string(ReturnModeName(std::get<1>(param_info.param)));
      std::erase(name, '-');
      return name;
    });

// The encoder against the test-only builder, which writes each field at the manual's offset.
TEST(PacketEncoder, MatchesTheByteBuilder) {
  DataPacketContent content;
  content.mode = ReturnMode::kLast;
  content.product_id = kProductIdVlp32c;
  content.us_past_hour = 0x12345678;
  testing::DataPacketBuilder builder(0x38, kProductIdVlp32c, 35950, 20);
  builder.Timestamp(0x12345678);
  for (int block = 0; block < 12; ++block) {
    content.block_azimuth_units[static_cast<std::size_t>(block)] =
        static_cast<std::uint16_t>((35950 + block * 20) % 36000);
    for (int c = 0; c < 32; ++c) {
      const auto distance = static_cast<std::uint16_t>(block * 1000 + c * 7 + 0x0100);
      const auto intensity = static_cast<std::uint8_t>(block * 32 + c);
      content.records[static_cast<std::size_t>(block)][static_cast<std::size_t>(c)] = {distance,
                                                                                       intensity};
      builder.Record(block, c, distance, intensity);
    }
  }
  const auto bytes = EncodeDataPacket(content);
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  EXPECT_EQ(*bytes, builder.array());
  EXPECT_EQ((*bytes)[0], 0xFF);
  EXPECT_EQ((*bytes)[1], 0xEE);
  EXPECT_EQ((*bytes)[1200], 0x78);
  EXPECT_EQ((*bytes)[1204], 0x38);
}

TEST(PacketEncoder, EncodingAndScheduleAllocateNothing) {
  DataPacketContent content;
  content.records[3][5] = {1234, 56};
  const std::uint64_t before = testing::AllocationCount();
  const auto bytes = EncodeDataPacket(content);
  const FiringSchedule schedule(Model::kVlp16, ReturnMode::kDual);
  EXPECT_EQ(testing::AllocationCount(), before);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(ReadU16(bytes->data() + 3 * 100 + 4 + 5 * 3), 1234);
  EXPECT_EQ(schedule.At(11, 31).fan, 23);
}

TEST(PacketEncoder, RejectsWhatWouldBeAMalformedPacket) {
  DataPacketContent content;
  content.block_azimuth_units[7] = 36000;
  const auto bad_azimuth = EncodeDataPacket(content);
  ASSERT_FALSE(bad_azimuth.ok());
  EXPECT_NE(bad_azimuth.error().message.find("block 7 azimuth 36000"), std::string::npos)
      << bad_azimuth.error().message;
  content.block_azimuth_units[7] = 35999;
  EXPECT_TRUE(EncodeDataPacket(content).ok());
  content.mode = static_cast<ReturnMode>(0x40);
  EXPECT_FALSE(EncodeDataPacket(content).ok());
  content.mode = ReturnMode::kDual;
  content.us_past_hour = 3'600'000'000u;
  EXPECT_FALSE(EncodeDataPacket(content).ok());
}

// (d) RawDistance is the decoder's range formula inverted to within half a unit, and 0 where
// no raw distance can carry the range.
TEST(RawDistance, InvertsTheDecoderWithinHalfAUnit) {
  std::mt19937 rng(kEncoderSeed);
  for (Model model : {Model::kVlp16, Model::kHdl32e, Model::kVlp32c}) {
    LaserTable table = DefaultLaserTable(model);
    table.lasers[3].distance_offset_m = 0.057;  // as a calibration file may give
    const double resolution = table.distance_resolution_m;
    std::uniform_real_distribution<double> range_m(0.3, 65535 * resolution);
    for (int i = 0; i < 2000; ++i) {
      const int laser = i % table.num_lasers;
      const double offset = table.lasers[static_cast<std::size_t>(laser)].distance_offset_m;
      const double range = range_m(rng);
      const std::uint16_t raw = RawDistance(range, table, laser);
      if (range - offset > 65535.5 * resolution) {
        EXPECT_EQ(raw, 0) << range;
        continue;
      }
      ASSERT_GT(raw, 0) << range;
      EXPECT_LE(std::abs(raw * resolution + offset - range), 0.5 * resolution + 1e-12) << range;
    }
    const double max_m = 65535 * resolution + table.lasers[3].distance_offset_m;
    EXPECT_EQ(RawDistance(max_m, table, 3), 65535);
    EXPECT_EQ(RawDistance(max_m + resolution, table, 3), 0);
    EXPECT_EQ(RawDistance(0.0, table, 0), 0);
    EXPECT_EQ(RawDistance(-1.0, table, 0), 0);
    EXPECT_EQ(RawDistance(0.4 * resolution, table, 0), 0);  // rounds to 0 units: no return
    EXPECT_EQ(RawDistance(std::nan(""), table, 0), 0);
    EXPECT_EQ(RawDistance(std::numeric_limits<double>::infinity(), table, 0), 0);
  }
}

// Reads the raw fields back out of a payload by the manual's layout, independently of the
// encoder (test-only).
DataPacketContent ReadRawContent(std::span<const std::uint8_t> payload) {
  const auto u16 = [&](std::size_t at) {
    return static_cast<std::uint16_t>(payload[at] | (payload[at + 1] << 8));
  };
  DataPacketContent content;
  for (std::size_t block = 0; block < 12; ++block) {
    content.block_azimuth_units[block] = u16(block * 100 + 2);
    for (std::size_t c = 0; c < 32; ++c) {
      const std::size_t at = block * 100 + 4 + c * 3;
      content.records[block][c] = {u16(at), payload[at + 2]};
    }
  }
  content.us_past_hour = static_cast<std::uint32_t>(u16(1200)) |
                         (static_cast<std::uint32_t>(u16(1202)) << 16);
  content.mode = static_cast<ReturnMode>(payload[1204]);
  content.product_id = payload[1205];
  return content;
}

struct RealCapture {
  const char* path;
  std::uint64_t data_packets;  // shared/data/PROVENANCE.md
};

void PrintTo(const RealCapture& capture, std::ostream* os) { *os << capture.path; }

class ReEncodeCapture : public ::testing::TestWithParam<RealCapture> {};

// (b) Every data packet of a real capture, read field by field and re-encoded, is
// byte-identical: the flags, byte order and factory bytes are the sensor's own.
TEST_P(ReEncodeCapture, EveryDataPacketIsByteIdentical) {
  FLAT2D_REQUIRE_DATA(path, std::string("velodyne/") + GetParam().path);
  auto source = net::OpenCapture(path);
  ASSERT_TRUE(source.ok()) << source.error().message;
  std::uint64_t packets = 0;
  while (const auto datagram = (*source)->Next()) {
    if (datagram->payload.size() != kDataPacketSize) continue;
    const auto bytes = EncodeDataPacket(ReadRawContent(datagram->payload));
    ASSERT_TRUE(bytes.ok()) << "packet " << packets << ": " << bytes.error().message;
    const auto mismatch =
        std::mismatch(bytes->begin(), bytes->end(), datagram->payload.begin()).first;
    ASSERT_EQ(mismatch, bytes->end())
        << "packet " << packets << " differs at byte " << (mismatch - bytes->begin());
    ++packets;
  }
  EXPECT_EQ(packets, GetParam().data_packets);
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, ReEncodeCapture,
    ::testing::Values(RealCapture{"vlp16/mrpt_sample_velodyne_vlp16_gps.pcap", 293},
                      RealCapture{"hdl32e/rust-lidar-utils_hdl32_example.pcap", 876},
                      RealCapture{"vlp32c/DERIVED_nebula_vlp32c_1713492677464078412.pcap", 379},
                      RealCapture{"vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap",
                                  603}),
    [](const ::testing::TestParamInfo<RealCapture>& param_info) {
      std::string name = std::filesystem::path(param_info.param.path).stem().string();
      std::replace_if(
          name.begin(), name.end(),
          [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
      return name;
    });

}  // namespace
}  // namespace flat2d::hal::velodyne
