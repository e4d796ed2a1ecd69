// Byte-exact tests of the data-packet decoder on hand-built packets of each model and
// return mode. Expected coordinates were computed by hand from the manuals' 9.2
// equations (x forward, y left: x = R cos(w) cos(a), y = -R cos(w) sin(a), z = R sin(w)).
#include "hal/velodyne/packet_decoder.hpp"

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"
#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::hal::velodyne {
namespace {

using flat2d::testing::DataPacketBuilder;

constexpr std::uint8_t kStrongest = 0x37, kLast = 0x38, kDual = 0x39;

DecodedPacket Decode(Model model, std::span<const std::uint8_t> bytes) {
  PacketDecoder decoder(DefaultLaserTable(model));
  DecodedPacket packet;
  decoder.Decode(bytes, packet);
  return packet;
}

TEST(PacketDecoder, Vlp16StrongestFirstRecordMatchesManualEquations) {
  const auto builder = DataPacketBuilder(kStrongest, 0x22, 0, 40)
                           .Record(0, 0, 5000, 77)  // laser 0 (-15 deg), 5000 x 2 mm = 10 m
                           .Timestamp(1'234'567'890);
  const DecodedPacket packet = Decode(Model::kVlp16, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  EXPECT_EQ(packet.us_past_hour, 1'234'567'890u);
  EXPECT_EQ(packet.return_mode, ReturnMode::kStrongest);
  EXPECT_EQ(packet.product_id, 0x22);
  EXPECT_EQ(packet.num_fans, 24);
  EXPECT_EQ(packet.num_points, 1);

  const LaserReturn& r = packet.fans[0].returns[0];
  EXPECT_FLOAT_EQ(r.range_m, 10.0f);
  EXPECT_EQ(r.intensity, 77);
  // Laser 0 sits 11.2 mm above the origin (manual Table 9-1 vertical correction).
  EXPECT_NEAR(r.xyz.x(), 9.662157, 1e-5);
  EXPECT_NEAR(r.xyz.y(), 0.0, 1e-6);
  EXPECT_NEAR(r.xyz.z(), -2.577372, 1e-5);
  // Every other record is a zero distance: no return.
  EXPECT_EQ(packet.fans[0].returns[1].range_m, 0.0f);
  EXPECT_EQ(packet.fans[1].returns[0].range_m, 0.0f);
}

TEST(PacketDecoder, Vlp16SecondFiringSequenceIsInterpolatedInTimeAndAzimuth) {
  const auto builder = DataPacketBuilder(kStrongest, 0x22, 1000, 40)
                           .Record(0, 16, 1000, 1)   // laser 0, second sequence
                           .Record(0, 17, 1000, 1);  // laser 1, second sequence
  const DecodedPacket packet = Decode(Model::kVlp16, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  // Fan 1 is block 0's second sequence: 55.296 us after the first, halfway to block 1.
  const Fan& fan = packet.fans[1];
  EXPECT_EQ(fan.stamp_ns, 55'296);
  EXPECT_NEAR(fan.azimuth_rad, 10.20 * kDegToRad, 1e-6);
  EXPECT_NEAR(fan.returns[0].azimuth_rad, 10.20 * kDegToRad, 1e-6);
  EXPECT_EQ(fan.returns[0].time_offset_ns, 0);
  // Laser 1 fires 2.304 us later: 40 x 57.6 / 110.592 = 20.83 -> 21 hundredths.
  EXPECT_NEAR(fan.returns[1].azimuth_rad, 10.21 * kDegToRad, 1e-6);
  EXPECT_EQ(fan.returns[1].time_offset_ns, 2'304);
  // Block 1 starts one block period (110.592 us) after block 0.
  EXPECT_EQ(packet.fans[2].stamp_ns, 110'592);
  EXPECT_EQ(packet.fans[23].stamp_ns, 11 * 110'592 + 55'296);
}

TEST(PacketDecoder, Hdl32eFiresLaserPairs1152NsApart) {
  const auto builder = DataPacketBuilder(kStrongest, 0x21, 8952, 16)
                           .Record(3, 5, 10000, 200);  // laser 5 (-6.67 deg), 20 m
  const DecodedPacket packet = Decode(Model::kHdl32e, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  EXPECT_EQ(packet.num_fans, 12);
  const Fan& fan = packet.fans[3];
  EXPECT_EQ(fan.num_lasers, 32);
  EXPECT_EQ(fan.stamp_ns, 3 * 46'080);
  const LaserReturn& r = fan.returns[5];
  EXPECT_EQ(r.time_offset_ns, 2 * 1'152);
  // Block azimuth 90.00 deg, + 16 x 2.304 / 46.08 = 0.8 -> 1 hundredth.
  EXPECT_NEAR(r.azimuth_rad, 90.01 * kDegToRad, 1e-6);
  EXPECT_NEAR(r.xyz.x(), -0.003467, 1e-5);
  EXPECT_NEAR(r.xyz.y(), -19.864632, 1e-4);
  EXPECT_NEAR(r.xyz.z(), -2.323014, 1e-4);
}

TEST(PacketDecoder, Vlp32cAppliesAzimuthOffsetAnd4mmUnits) {
  const auto builder = DataPacketBuilder(kStrongest, 0x28, 35950, 20)
                           .Record(0, 0, 2500, 9);  // laser 0: -25 deg, +1.4 deg azimuth
  const DecodedPacket packet = Decode(Model::kVlp32c, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  const LaserReturn& r = packet.fans[0].returns[0];
  EXPECT_FLOAT_EQ(r.range_m, 10.0f);  // 2500 x 4 mm
  EXPECT_NEAR(r.azimuth_rad, 0.90 * kDegToRad, 1e-6);  // 359.50 + 1.40 wraps to 0.90
  EXPECT_NEAR(r.xyz.x(), 9.061960, 1e-5);
  EXPECT_NEAR(r.xyz.y(), -0.142357, 1e-5);
  EXPECT_NEAR(r.xyz.z(), -4.226183, 1e-5);
  EXPECT_EQ(packet.fans[1].stamp_ns, 55'296);
}

TEST(PacketDecoder, DualReturnPairsShareFiringAndInterleaveByTime) {
  DataPacketBuilder builder(kDual, 0x22);
  for (int block = 0; block < 12; ++block) builder.BlockAzimuth(block, 500 + (block / 2) * 40);
  builder.Record(0, 0, 6000, 10)   // last return, laser 0, 12 m
      .Record(1, 0, 5000, 90);     // strongest return of the same firing, 10 m
  const DecodedPacket packet = Decode(Model::kVlp16, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  EXPECT_EQ(packet.num_fans, 24);
  EXPECT_EQ(packet.num_points, 2);
  EXPECT_EQ(packet.fans[0].kind, ReturnKind::kLast);
  EXPECT_EQ(packet.fans[1].kind, ReturnKind::kStrongest);
  EXPECT_FLOAT_EQ(packet.fans[0].returns[0].range_m, 12.0f);
  EXPECT_FLOAT_EQ(packet.fans[1].returns[0].range_m, 10.0f);
  EXPECT_EQ(packet.fans[0].stamp_ns, packet.fans[1].stamp_ns);
  EXPECT_EQ(packet.fans[2].stamp_ns, 55'296);   // second sequence of the first firing
  EXPECT_EQ(packet.fans[4].stamp_ns, 110'592);  // blocks 2 and 3: the second firing
  for (int f = 1; f < packet.num_fans; ++f) {
    EXPECT_LE(packet.fans[f - 1].stamp_ns, packet.fans[f].stamp_ns) << "fan " << f;
  }
  // The azimuth gap of a dual pair is to the next pair (40 hundredths), not 0.
  EXPECT_NEAR(packet.fans[2].azimuth_rad, 5.20 * kDegToRad, 1e-6);
}

TEST(PacketDecoder, LastReturnModeMarksFansLast) {
  const auto builder = DataPacketBuilder(kLast, 0x22).Record(2, 3, 100, 1);
  const DecodedPacket packet = Decode(Model::kVlp16, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  EXPECT_EQ(packet.return_mode, ReturnMode::kLast);
  EXPECT_EQ(packet.fans[4].kind, ReturnKind::kLast);
  EXPECT_FLOAT_EQ(packet.fans[4].returns[3].range_m, 0.2f);
}

TEST(PacketDecoder, AzimuthJumpInsidePacketReusesLastGap) {
  DataPacketBuilder builder(kStrongest, 0x28, 9000, 20);
  for (int block = 6; block < 12; ++block) builder.BlockAzimuth(block, 27000 + (block - 6) * 20);
  builder.Record(5, 2, 1000, 1);  // laser 2 fires 2.304 us into block 5, just before the jump
  const DecodedPacket packet = Decode(Model::kVlp32c, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  // 91.00 + 20 x 2.304 / 55.296 (0.83 -> 1) + 1.40 offset, not an interpolation over 179 deg.
  EXPECT_NEAR(packet.fans[5].returns[2].azimuth_rad, 92.41 * kDegToRad, 1e-6);
  EXPECT_NEAR(packet.fans[6].azimuth_rad, 270.0 * kDegToRad, 1e-6);
}

TEST(PacketDecoder, RejectsMalformedPacketsWithReason) {
  PacketDecoder decoder(DefaultLaserTable(Model::kVlp16));
  DecodedPacket packet;
  const DataPacketBuilder good(kStrongest, 0x22);
  std::vector<std::uint8_t> bytes(good.bytes().begin(), good.bytes().end());

  decoder.Decode(std::span(bytes).first(1205), packet);
  EXPECT_EQ(packet.error, PacketError::kWrongSize);
  EXPECT_EQ(packet.num_fans, 0);
  bytes.push_back(0);
  decoder.Decode(bytes, packet);
  EXPECT_EQ(packet.error, PacketError::kWrongSize);
  bytes.pop_back();

  auto flagged = DataPacketBuilder(kStrongest, 0x22).BlockFlag(7, 0xFF, 0xDD);
  decoder.Decode(flagged.bytes(), packet);
  EXPECT_EQ(packet.error, PacketError::kBadBlockFlag);

  auto azimuth = DataPacketBuilder(kStrongest, 0x22).BlockAzimuth(3, 36000);
  decoder.Decode(azimuth.bytes(), packet);
  EXPECT_EQ(packet.error, PacketError::kAzimuthOutOfRange);

  auto mode = DataPacketBuilder(0x40, 0x22);
  decoder.Decode(mode.bytes(), packet);
  EXPECT_EQ(packet.error, PacketError::kUnknownReturnMode);
  EXPECT_EQ(packet.num_fans, 0);

  decoder.Decode(good.bytes(), packet);  // a bad packet leaves the decoder usable
  EXPECT_EQ(packet.error, PacketError::kNone);
}

TEST(PacketDecoder, MaximumDistanceDecodesWithoutOverflow) {
  const auto builder = DataPacketBuilder(kStrongest, 0x21).Record(0, 0, 0xFFFF, 255);
  const DecodedPacket packet = Decode(Model::kHdl32e, builder.bytes());
  EXPECT_NEAR(packet.fans[0].returns[0].range_m, 131.07, 1e-3);
  EXPECT_EQ(packet.fans[0].returns[0].intensity, 255);
}

// Every model in every return mode: fan count, return kinds, firing times and the point
// count, from the manuals' tables (block period 110.592 / 46.080 / 55.296 us).
struct ModeCase {
  Model model;
  std::uint8_t mode_byte;
  int fans;
  std::int64_t firing_period_ns;
};

class EveryModelAndMode : public ::testing::TestWithParam<ModeCase> {};

TEST_P(EveryModelAndMode, FansKindsAndStamps) {
  const ModeCase& c = GetParam();
  const bool dual = c.mode_byte == kDual;
  DataPacketBuilder builder(c.mode_byte, 0x22);
  for (int block = 0; block < 12; ++block) {
    builder.BlockAzimuth(block, 100 + (dual ? block / 2 : block) * 20);
    builder.Record(block, 1, static_cast<std::uint16_t>(1000 + block), 7);
  }
  const DecodedPacket packet = Decode(c.model, builder.bytes());
  ASSERT_EQ(packet.error, PacketError::kNone);
  EXPECT_EQ(packet.num_fans, c.fans);
  EXPECT_EQ(packet.num_points, 12);
  const int fans_per_firing = c.fans / (dual ? 6 : 12);
  for (int f = 0; f < packet.num_fans; ++f) {
    const Fan& fan = packet.fans[static_cast<std::size_t>(f)];
    const int firing = f / fans_per_firing;
    const int sequence = dual ? (f % fans_per_firing) / 2 : f % fans_per_firing;
    EXPECT_EQ(fan.stamp_ns, firing * c.firing_period_ns + sequence * 55'296) << "fan " << f;
    const ReturnKind expected_kind = c.mode_byte == kStrongest ? ReturnKind::kStrongest
                                     : c.mode_byte == kLast    ? ReturnKind::kLast
                                     : f % 2 == 0              ? ReturnKind::kLast
                                                               : ReturnKind::kStrongest;
    EXPECT_EQ(fan.kind, expected_kind) << "fan " << f;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Velodyne, EveryModelAndMode,
    ::testing::Values(ModeCase{Model::kVlp16, kStrongest, 24, 110'592},
                      ModeCase{Model::kVlp16, kLast, 24, 110'592},
                      ModeCase{Model::kVlp16, kDual, 24, 110'592},
                      ModeCase{Model::kHdl32e, kStrongest, 12, 46'080},
                      ModeCase{Model::kHdl32e, kLast, 12, 46'080},
                      ModeCase{Model::kHdl32e, kDual, 12, 46'080},
                      ModeCase{Model::kVlp32c, kStrongest, 12, 55'296},
                      ModeCase{Model::kVlp32c, kLast, 12, 55'296},
                      ModeCase{Model::kVlp32c, kDual, 12, 55'296}));

}  // namespace
}  // namespace flat2d::hal::velodyne
