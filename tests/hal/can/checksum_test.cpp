// Toyota and Honda checksums on frames worked by hand from the algorithm (opendbc
// common.cc), and their detection from DBC layouts.
#include "hal/can/checksum.hpp"

#include <algorithm>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

namespace flat2d::hal::can {
namespace {

CanFrame Frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, bool extended = false) {
  CanFrame frame;
  frame.id = id;
  frame.extended = extended;
  frame.length = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), frame.data.begin());
  return frame;
}

TEST(ChecksumTest, ToyotaSumOfIdLengthAndData) {
  // Real RAV4 frame 0B4#000000001D0B7A5E: 0x00 + 0xB4 + 8 + 0x1D + 0x0B + 0x7A = 0x15E.
  const CanFrame speed = Frame(0xB4, {0x00, 0x00, 0x00, 0x00, 0x1D, 0x0B, 0x7A, 0x5E});
  EXPECT_EQ(ToyotaChecksum(speed.id, speed.payload()), 0x5E);
  EXPECT_TRUE(VerifyChecksum(ChecksumKind::kToyota, speed));
  // Both id bytes count: 0x2E4 -> 0x02 + 0xE4; 5 bytes.
  const CanFrame lka = Frame(0x2E4, {0x01, 0x02, 0x03, 0x04, 0x02 + 0xE4 + 5 + 1 + 2 + 3 + 4});
  EXPECT_TRUE(VerifyChecksum(ChecksumKind::kToyota, lka));
  // Every single-bit error in the covered bytes is caught (a sum changes by 2^k).
  for (std::size_t bit = 0; bit < 64; ++bit) {
    CanFrame corrupted = speed;
    corrupted.data[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(VerifyChecksum(ChecksumKind::kToyota, corrupted)) << "bit " << bit;
  }
  EXPECT_FALSE(VerifyChecksum(ChecksumKind::kToyota, Frame(0xB4, {})));
}

TEST(ChecksumTest, HondaNibbleSum) {
  // Real Civic frame 14A#FFF1000007FFF124: id nibbles 1+4+A = 15; data nibbles
  // F+F, F+1, 0, 0, 0+7, F+F, F+1 and the checksum byte's high nibble 2: 101.
  // (8 - 116) & 0xF = 4, the low nibble of the last byte.
  const CanFrame steering = Frame(0x14A, {0xFF, 0xF1, 0x00, 0x00, 0x07, 0xFF, 0xF1, 0x24});
  EXPECT_EQ(HondaChecksum(steering.id, false, steering.payload()), 4);
  EXPECT_TRUE(VerifyChecksum(ChecksumKind::kHonda, steering));
  // The counter bits (high nibble of the last byte) are covered too.
  CanFrame counter_changed = steering;
  counter_changed.data[7] = 0x34;
  EXPECT_FALSE(VerifyChecksum(ChecksumKind::kHonda, counter_changed));
  // A 29-bit id adds 3 (opendbc: "extended can").
  EXPECT_EQ(HondaChecksum(0x14A, true, steering.payload()), 7);
  EXPECT_EQ(HondaChecksum(0x33DA, false, steering.payload()), HondaChecksum(0x33DA, true, steering.payload()));
}

TEST(ChecksumTest, NoneAlwaysVerifies) {
  EXPECT_TRUE(VerifyChecksum(ChecksumKind::kNone, Frame(1, {})));
}

TEST(ChecksumTest, KindNamesRoundTrip) {
  for (ChecksumKind kind : {ChecksumKind::kNone, ChecksumKind::kToyota, ChecksumKind::kHonda}) {
    EXPECT_EQ(ParseChecksumKind(ChecksumKindName(kind)), kind);
  }
  EXPECT_FALSE(ParseChecksumKind("crc8").has_value());
}

DbcMessage MessageWith(std::uint8_t dlc, std::uint16_t start, std::uint8_t length, bool intel = false) {
  // std::string("..."), not = "...": GCC 12 -O3 misfires -Wrestrict on the latter.
  DbcMessage message;
  message.name = std::string("M");
  message.dlc = dlc;
  DbcSignal checksum;
  checksum.name = std::string("CHECKSUM");
  checksum.start_bit = start;
  checksum.length = length;
  checksum.little_endian = intel;
  message.signals.push_back(checksum);
  return message;
}

TEST(ChecksumTest, DetectsLayouts) {
  EXPECT_EQ(DetectChecksum(MessageWith(8, 63, 8)), ChecksumKind::kToyota);
  EXPECT_EQ(DetectChecksum(MessageWith(5, 39, 8)), ChecksumKind::kToyota);  // EPS_STATUS
  EXPECT_EQ(DetectChecksum(MessageWith(8, 56, 8, true)), ChecksumKind::kToyota);
  EXPECT_EQ(DetectChecksum(MessageWith(8, 59, 4)), ChecksumKind::kHonda);
  EXPECT_EQ(DetectChecksum(MessageWith(3, 19, 4)), ChecksumKind::kHonda);  // STEER_MOTOR_TORQUE
  EXPECT_EQ(DetectChecksum(MessageWith(8, 7, 8)), ChecksumKind::kNone);    // first byte: not ours
  EXPECT_EQ(DetectChecksum(MessageWith(8, 63, 4)), ChecksumKind::kNone);   // high nibble
  DbcMessage renamed = MessageWith(8, 63, 8);
  renamed.signals[0].name = std::string("CHECKSUM_PEDAL");
  EXPECT_EQ(DetectChecksum(renamed), ChecksumKind::kNone);
}

TEST(ChecksumTest, OverridesWinOverDetection) {
  const DbcMessage toyota = MessageWith(8, 63, 8);
  ChecksumOptions options;
  EXPECT_EQ(SelectChecksum(toyota, options), ChecksumKind::kToyota);
  options.detect = false;
  EXPECT_EQ(SelectChecksum(toyota, options), ChecksumKind::kNone);
  options.overrides.push_back({"M", ChecksumKind::kHonda});
  EXPECT_EQ(SelectChecksum(toyota, options), ChecksumKind::kHonda);
}

}  // namespace
}  // namespace flat2d::hal::can
