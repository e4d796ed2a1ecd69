// FrameDecoder: selection by name, decoding by id, checksum marking, multiplexing, short
// frames, and the allocation-free hot path.
#include "hal/can/frame_decoder.hpp"

#include <algorithm>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::can {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// RAV4 definitions (opendbc toyota_rav4_hybrid_2017_pt_generated.dbc) plus a multiplexed
// message shaped like strym's TRACK_B_1 and an extended-id message.
constexpr const char* kDbc = R"(
BO_ 37 STEER_ANGLE_SENSOR: 8 XXX
 SG_ STEER_ANGLE : 3|12@0- (1.5,0) [-500|500] "deg" XXX
 SG_ STEER_FRACTION : 39|4@0- (0.1,0) [-0.7|0.7] "deg" XXX

BO_ 170 WHEEL_SPEEDS: 8 XXX
 SG_ WHEEL_SPEED_FR : 7|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
 SG_ WHEEL_SPEED_RL : 55|16@0+ (0.01,-67.67) [0|250] "km/h" XXX

BO_ 180 SPEED: 8 XXX
 SG_ SPEED : 47|16@0+ (0.01,0) [0|250] "km/h" XXX
 SG_ CHECKSUM : 63|8@0+ (1,0) [0|255] "" XXX

BO_ 401 TRACK_B_1: 8 XXX
 SG_ MUX M : 7|1@0+ (1,0) [0|0] "" XXX
 SG_ COUNTER m1: 6|6@0+ (1,0) [0|255] "" XXX
 SG_ COUNTER m0: 15|8@0+ (1,0) [0|255] "" XXX
 SG_ ANGLE m0: 23|8@0- (0.5,0) [0|255] "" XXX

BO_ 2147484008 EXT: 2 XXX
 SG_ VALUE : 0|16@1+ (1,0) [0|0] "" XXX
)";

Dbc TestDbc() {
  auto dbc = ParseDbc(kDbc, "test.dbc");
  EXPECT_TRUE(dbc.ok()) << (dbc.ok() ? "" : dbc.error().message);
  return dbc.ok() ? std::move(*dbc) : Dbc{};
}

FrameDecoder MakeDecoder(const std::vector<SignalSelection>& selection, const ChecksumOptions& options = {}) {
  auto decoder = FrameDecoder::Create(TestDbc(), selection, options);
  EXPECT_TRUE(decoder.ok()) << (decoder.ok() ? "" : decoder.error().message);
  return std::move(*decoder);
}

CanFrame Frame(std::uint32_t id, std::vector<std::uint8_t> bytes, TimeNs time_ns = 0, bool extended = false) {
  CanFrame frame;
  frame.id = id;
  frame.extended = extended;
  frame.time_ns = time_ns;
  frame.length = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), frame.data.begin());
  return frame;
}

std::vector<std::size_t> Updated(const FrameDecoder& decoder) {
  return {decoder.updated().begin(), decoder.updated().end()};
}

TEST(FrameDecoderTest, DecodesSelectedSignalsById) {
  FrameDecoder decoder = MakeDecoder({{"WHEEL_SPEEDS", "WHEEL_SPEED_RL"},
                                      {"STEER_ANGLE_SENSOR", "STEER_ANGLE"},
                                      {"WHEEL_SPEEDS", "WHEEL_SPEED_FR"}});
  EXPECT_EQ(decoder.Decode(Frame(0xAA, {0x1A, 0x2B, 0, 0, 0, 0, 0x25, 0x8D}, 123)), FrameStatus::kDecoded);
  EXPECT_THAT(Updated(decoder), ElementsAre(0u, 2u));
  EXPECT_NEAR(decoder.values()[2].value, 0x1A2B * 0.01 - 67.67, 1e-9);
  EXPECT_NEAR(decoder.values()[0].value, 0x258D * 0.01 - 67.67, 1e-9);
  EXPECT_EQ(decoder.values()[0].time_ns, 123);
  EXPECT_EQ(decoder.values()[1].updates, 0u);
  EXPECT_EQ(decoder.Decode(Frame(0x25, {0x0F, 0xF6, 0, 0, 0, 0, 0, 0}, 124)), FrameStatus::kDecoded);
  EXPECT_DOUBLE_EQ(decoder.values()[1].value, -15.0);
  EXPECT_EQ(decoder.Decode(Frame(0x24, {0, 0, 0, 0, 0, 0, 0, 0})), FrameStatus::kIgnored);
  EXPECT_TRUE(decoder.updated().empty());
  EXPECT_EQ(decoder.IndexOf("STEER_ANGLE_SENSOR", "STEER_ANGLE"), 1u);
  EXPECT_FALSE(decoder.IndexOf("STEER_ANGLE_SENSOR", "STEER_FRACTION").has_value());
  EXPECT_EQ(decoder.stats().frames, 3u);
  EXPECT_EQ(decoder.stats().decoded, 2u);
  EXPECT_EQ(decoder.stats().ignored, 1u);
}

TEST(FrameDecoderTest, ExtendedIdsDoNotMatchStandardOnes) {
  FrameDecoder decoder = MakeDecoder({{"EXT", "VALUE"}});
  EXPECT_EQ(decoder.Decode(Frame(360, {0x34, 0x12})), FrameStatus::kIgnored);
  EXPECT_EQ(decoder.Decode(Frame(360, {0x34, 0x12}, 0, true)), FrameStatus::kDecoded);
  EXPECT_DOUBLE_EQ(decoder.values()[0].value, 0x1234);
}

TEST(FrameDecoderTest, ChecksumFailuresAreCountedAndUpdateNothing) {
  FrameDecoder decoder = MakeDecoder({{"SPEED", "SPEED"}});
  ASSERT_EQ(decoder.messages().size(), 1u);
  EXPECT_EQ(decoder.messages()[0].checksum(), ChecksumKind::kToyota);  // detected from the DBC
  const CanFrame good = Frame(0xB4, {0x00, 0x00, 0x00, 0x00, 0x1D, 0x0B, 0x7A, 0x5E});
  EXPECT_EQ(decoder.Decode(good), FrameStatus::kDecoded);
  CanFrame bad = good;
  bad.data[5] ^= 0x10;
  EXPECT_EQ(decoder.Decode(bad), FrameStatus::kChecksumFailed);
  EXPECT_NEAR(decoder.values()[0].value, 29.38, 1e-9);  // kept from the good frame
  EXPECT_EQ(decoder.values()[0].updates, 1u);
  EXPECT_EQ(decoder.stats().checksum_checked, 2u);
  EXPECT_EQ(decoder.stats().checksum_failures, 1u);
  // Configuration can switch verification off.
  FrameDecoder unchecked = MakeDecoder({{"SPEED", "SPEED"}}, {.detect = false, .overrides = {}});
  EXPECT_EQ(unchecked.Decode(bad), FrameStatus::kDecoded);
  // ... or name a kind for a message whose DBC entry has no CHECKSUM signal.
  ChecksumOptions configured;
  configured.overrides.push_back({"STEER_ANGLE_SENSOR", ChecksumKind::kToyota});
  FrameDecoder forced = MakeDecoder({{"STEER_ANGLE_SENSOR", "STEER_ANGLE"}}, configured);
  EXPECT_EQ(forced.Decode(Frame(0x25, {0, 0, 0, 0, 0, 0, 0, 0})), FrameStatus::kChecksumFailed);
  EXPECT_EQ(forced.Decode(Frame(0x25, {0, 0, 0, 0, 0, 0, 0, 0x25 + 8})), FrameStatus::kDecoded);
}

TEST(FrameDecoderTest, MultiplexedSignalsFollowTheSwitch) {
  FrameDecoder decoder = MakeDecoder({{"TRACK_B_1", "COUNTER"}, {"TRACK_B_1", "ANGLE"}});
  // Switch 1 (bit 7 of byte 0): COUNTER m1 is bits 6..1 of byte 0; ANGLE (m0) absent.
  EXPECT_EQ(decoder.Decode(Frame(401, {0x80 | (0x2A << 1), 0xFF, 0xFF, 0, 0, 0, 0, 0})), FrameStatus::kDecoded);
  EXPECT_THAT(Updated(decoder), ElementsAre(0u));
  EXPECT_DOUBLE_EQ(decoder.values()[0].value, 0x2A);
  // Switch 0: COUNTER m0 is byte 1, ANGLE byte 2 signed: 0xFE = -2 -> -1.0.
  EXPECT_EQ(decoder.Decode(Frame(401, {0x00, 0x07, 0xFE, 0, 0, 0, 0, 0})), FrameStatus::kDecoded);
  EXPECT_THAT(Updated(decoder), ElementsAre(0u, 1u));
  EXPECT_DOUBLE_EQ(decoder.values()[0].value, 7.0);
  EXPECT_DOUBLE_EQ(decoder.values()[1].value, -1.0);
  EXPECT_EQ(decoder.values()[0].updates, 2u);
}

TEST(FrameDecoderTest, ShortFramesAreCountedAndDecodeWhatFits) {
  FrameDecoder decoder = MakeDecoder({{"WHEEL_SPEEDS", "WHEEL_SPEED_FR"}, {"WHEEL_SPEEDS", "WHEEL_SPEED_RL"}});
  EXPECT_EQ(decoder.Decode(Frame(0xAA, {0x1A, 0x2B, 0, 0})), FrameStatus::kTooShort);
  EXPECT_THAT(Updated(decoder), ElementsAre(0u));
  EXPECT_EQ(decoder.values()[1].updates, 0u);
  EXPECT_EQ(decoder.stats().too_short, 1u);
  // A remote frame carries no data: ignored, never "too short".
  CanFrame remote = Frame(0xAA, {});
  remote.remote = true;
  remote.length = 8;
  EXPECT_EQ(decoder.Decode(remote), FrameStatus::kIgnored);
}

TEST(FrameDecoderTest, SelectionErrorsNameTheEntry) {
  const Dbc dbc = TestDbc();
  auto missing = FrameDecoder::Create(dbc, std::vector<SignalSelection>{{"WHEEL_SPEEDS", "WHEEL_SPEED_XX"}});
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.error().message,
              HasSubstr("WHEEL_SPEEDS.WHEEL_SPEED_XX: message WHEEL_SPEEDS has no signal"));
  auto no_message = FrameDecoder::Create(dbc, std::vector<SignalSelection>{{"WHEELS", "X"}});
  ASSERT_FALSE(no_message.ok());
  EXPECT_THAT(no_message.error().message, HasSubstr("test.dbc has no message WHEELS"));
  auto twice = FrameDecoder::Create(dbc, std::vector<SignalSelection>{{"SPEED", "SPEED"}, {"SPEED", "SPEED"}});
  ASSERT_FALSE(twice.ok());
  EXPECT_THAT(twice.error().message, HasSubstr("SPEED.SPEED: selected twice"));
  ChecksumOptions typo;
  typo.overrides.push_back({"SPEEED", ChecksumKind::kToyota});
  auto bad_override = FrameDecoder::Create(dbc, std::vector<SignalSelection>{{"SPEED", "SPEED"}}, typo);
  ASSERT_FALSE(bad_override.ok());
  EXPECT_THAT(bad_override.error().message, HasSubstr("names message SPEEED, which test.dbc does not define"));
}

TEST(FrameDecoderTest, AllSignalsListsEachNameOnce) {
  const std::vector<SignalSelection> all = AllSignals(TestDbc());
  EXPECT_EQ(all.size(), 10u);  // TRACK_B_1's two COUNTER definitions share one entry
  auto decoder = FrameDecoder::Create(TestDbc(), all);
  EXPECT_TRUE(decoder.ok());
}

TEST(FrameDecoderTest, DecodeAllocatesNothing) {
  FrameDecoder decoder = MakeDecoder(AllSignals(TestDbc()));
  const std::vector<CanFrame> frames = {
      Frame(0xAA, {0x1A, 0x2B, 0, 0, 0, 0, 0x25, 0x8D}), Frame(0x25, {0x0F, 0xF6, 0, 0, 0xA0, 0, 0, 0}),
      Frame(0xB4, {0x00, 0x00, 0x00, 0x00, 0x1D, 0x0B, 0x7A, 0x5F}), Frame(401, {0x80, 1, 2, 3, 4, 5, 6, 7}),
      Frame(401, {0x00, 1, 2, 3, 4, 5, 6, 7}), Frame(0xAA, {1, 2}), Frame(0x7FF, {})};
  decoder.Decode(frames[0]);  // warm-up
  const std::uint64_t before = flat2d::testing::AllocationCount();
  for (int lap = 0; lap < 1000; ++lap) {
    for (const CanFrame& frame : frames) decoder.Decode(frame);
  }
  EXPECT_EQ(flat2d::testing::AllocationCount(), before);
  EXPECT_EQ(decoder.stats().frames, 7001u);
}

}  // namespace
}  // namespace flat2d::hal::can
