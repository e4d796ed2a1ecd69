// Signal extraction against frames computed by hand from the DBC bit numbering (Vector
// DBC spec: Intel start = LSB, Motorola start = MSB in the sawtooth numbering), and
// against an independent bit-by-bit reference on seeded random layouts.
#include "hal/can/signal_decoder.hpp"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/hal/can/test_signal.hpp"

namespace flat2d::hal::can {
namespace {

using test::Signal;

CompiledSignal Compile(const DbcSignal& signal) {
  auto compiled = CompiledSignal::Compile(signal);
  EXPECT_TRUE(compiled.ok()) << (compiled.ok() ? "" : compiled.error().message);
  return compiled.ok() ? *compiled : CompiledSignal{};
}

std::uint64_t RawOf(const DbcSignal& signal, const std::vector<std::uint8_t>& payload) {
  const auto raw = Compile(signal).Raw(payload);
  EXPECT_TRUE(raw.has_value());
  return raw.value_or(0xDEADBEEF);
}

TEST(SignalDecoderTest, IntelSignalsAcrossByteBoundaries) {
  // 4|12@1: bits 4..7 of byte 0 are the low nibble, byte 1 the high byte.
  EXPECT_EQ(RawOf(Signal(4, 12, true, false), {0xA0, 0xBC}), 0xBCAu);
  // 8|16@1: little-endian u16 in bytes 1-2.
  EXPECT_EQ(RawOf(Signal(8, 16, true, false), {0xFF, 0x34, 0x12}), 0x1234u);
  // 13|1@1: bit 5 of byte 1.
  EXPECT_EQ(RawOf(Signal(13, 1, true, false), {0x00, 0x20}), 1u);
  EXPECT_EQ(RawOf(Signal(13, 1, true, false), {0xFF, 0xDF}), 0u);
}

TEST(SignalDecoderTest, MotorolaSignalsUseTheSawtoothNumbering) {
  // 7|16@0: big-endian u16 in bytes 0-1.
  EXPECT_EQ(RawOf(Signal(7, 16, false, false), {0x1A, 0x2B}), 0x1A2Bu);
  // 3|12@0: bits 3..0 of byte 0 are the high nibble, byte 1 the low byte.
  EXPECT_EQ(RawOf(Signal(3, 12, false, false), {0xF5, 0x67}), 0x567u);
  // 1|10@0: bits 1..0 of byte 0, then byte 1.
  EXPECT_EQ(RawOf(Signal(1, 10, false, false), {0xFE, 0x00}), 0x200u);
  // 0|12@0 straddles three bytes: bit 0 of byte 0, byte 1, bits 7..5 of byte 2.
  EXPECT_EQ(RawOf(Signal(0, 12, false, false), {0x01, 0x00, 0x00}), 0x800u);
  EXPECT_EQ(RawOf(Signal(0, 12, false, false), {0xFE, 0xFF, 0xE0}), 0x7FFu);
  // 39|1@0: bit 7 of byte 4.
  EXPECT_EQ(RawOf(Signal(39, 1, false, false), {0, 0, 0, 0, 0x80}), 1u);
}

TEST(SignalDecoderTest, SignedValuesAreSignExtended) {
  // 4|12@1-: raw 0xFF1 = -15.
  const CompiledSignal intel = Compile(Signal(4, 12, true, true));
  const std::vector<std::uint8_t> intel_frame = {0x10, 0xFF};
  EXPECT_EQ(intel.SignedRaw(*intel.Raw(intel_frame)), -15);
  // 3|12@0- (1.5,0), RAV4 STEER_ANGLE: raw 0xFF6 = -10 -> -15 deg.
  const CompiledSignal steer = Compile(Signal(3, 12, false, true, 1.5, 0.0));
  EXPECT_DOUBLE_EQ(*steer.Decode(std::vector<std::uint8_t>{0x0F, 0xF6}), -15.0);
  // The positive limit stays positive: 0x7FF = 2047.
  EXPECT_DOUBLE_EQ(*steer.Decode(std::vector<std::uint8_t>{0x07, 0xFF}), 2047 * 1.5);
  // 39|4@0- (0.1,0), RAV4 STEER_FRACTION: high nibble of byte 4 = 0xA = -6 -> -0.6 deg.
  const CompiledSignal fraction = Compile(Signal(39, 4, false, true, 0.1, 0.0));
  EXPECT_NEAR(*fraction.Decode(std::vector<std::uint8_t>{0, 0, 0, 0, 0xA0}), -0.6, 1e-12);
  // 0|12@0-: raw 0x800 is the most negative 12-bit value.
  EXPECT_DOUBLE_EQ(*Compile(Signal(0, 12, false, true)).Decode(std::vector<std::uint8_t>{1, 0, 0}), -2048.0);
  // 1-bit signed: the only bit is the sign bit.
  EXPECT_DOUBLE_EQ(*Compile(Signal(0, 1, true, true)).Decode(std::vector<std::uint8_t>{1}), -1.0);
}

TEST(SignalDecoderTest, SixtyFourBitSignals) {
  const std::vector<std::uint8_t> frame = {0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF};
  EXPECT_EQ(RawOf(Signal(0, 64, true, false), frame), 0xEFCDAB8967452301u);
  EXPECT_EQ(RawOf(Signal(7, 64, false, false), frame), 0x0123456789ABCDEFu);
  EXPECT_EQ(Compile(Signal(0, 64, true, true)).SignedRaw(0xEFCDAB8967452301u), -1167088121787636991);
  // Starting mid-byte, 64 bits touch 9 bytes: too long for classic CAN, fine for CAN FD.
  const CompiledSignal shifted = Compile(Signal(4, 64, true, false));
  EXPECT_EQ(shifted.bytes_needed(), 9u);
  EXPECT_FALSE(shifted.Raw(frame).has_value());
  std::vector<std::uint8_t> fd(12, 0);
  fd[0] = 0xF0;  // bits 4..7 of byte 0 -> value bits 0..3
  fd[8] = 0x0F;  // bits 0..3 of byte 8 -> value bits 60..63
  EXPECT_EQ(shifted.Raw(fd), 0xF00000000000000Fu);
}

TEST(SignalDecoderTest, Rav4SignalsFromProvenance) {
  // WHEEL_SPEED_FR 7|16@0+ (0.01,-67.67) km/h: raw 0x1A2B in bytes 0-1.
  const CompiledSignal wheel = Compile(Signal(7, 16, false, false, 0.01, -67.67));
  EXPECT_NEAR(*wheel.Decode(std::vector<std::uint8_t>{0x1A, 0x2B, 0, 0, 0, 0, 0, 0}), 0x1A2B * 0.01 - 67.67,
              1e-9);
  // WHEEL_SPEED_RL 55|16@0+: bytes 6-7.
  const CompiledSignal rear_left = Compile(Signal(55, 16, false, false, 0.01, -67.67));
  EXPECT_NEAR(*rear_left.Decode(std::vector<std::uint8_t>{0, 0, 0, 0, 0, 0, 0x25, 0x8D}), 0x258D * 0.01 - 67.67,
              1e-9);
  // SPEED 47|16@0+ (0.01,0) km/h, real frame 0B4#000000001D0B7A5E: bytes 5-6 = 0x0B7A.
  const CompiledSignal speed = Compile(Signal(47, 16, false, false, 0.01, 0.0));
  EXPECT_NEAR(*speed.Decode(std::vector<std::uint8_t>{0x00, 0x00, 0x00, 0x00, 0x1D, 0x0B, 0x7A, 0x5E}), 29.38,
              1e-9);
  // YAW_RATE 1|10@0+ (0.244,-125) deg/s: raw 512 -> -0.072.
  const CompiledSignal yaw = Compile(Signal(1, 10, false, false, 0.244, -125.0));
  EXPECT_NEAR(*yaw.Decode(std::vector<std::uint8_t>{0x02, 0x00, 0, 0, 0, 0, 0, 0}), -0.072, 1e-9);
  // ACCEL_Y 33|10@0+ (0.03589,-18.375): bits 1..0 of byte 4, then byte 5: raw 0x3FF.
  const CompiledSignal accel = Compile(Signal(33, 10, false, false, 0.03589, -18.375));
  EXPECT_NEAR(*accel.Decode(std::vector<std::uint8_t>{0, 0, 0, 0, 0x03, 0xFF, 0, 0}), 1023 * 0.03589 - 18.375,
              1e-9);
}

TEST(SignalDecoderTest, ShortPayloadIsAnErrorValue) {
  const CompiledSignal rear = Compile(Signal(55, 16, false, false));
  EXPECT_EQ(rear.bytes_needed(), 8u);
  EXPECT_FALSE(rear.Raw(std::vector<std::uint8_t>(7, 0xFF)).has_value());
  EXPECT_FALSE(rear.Decode(std::span<const std::uint8_t>()).has_value());
  EXPECT_TRUE(rear.Raw(std::vector<std::uint8_t>(8, 0xFF)).has_value());
}

TEST(SignalDecoderTest, IeeeValueTypes) {
  DbcSignal single = Signal(0, 32, true, false, 2.0, 1.0);
  single.value_type = DbcValueType::kFloat32;
  // 1.5f = 0x3FC00000, little-endian in bytes 0-3.
  EXPECT_DOUBLE_EQ(*Compile(single).Decode(std::vector<std::uint8_t>{0x00, 0x00, 0xC0, 0x3F}), 4.0);
  DbcSignal wrong = Signal(0, 16, true, false);
  wrong.value_type = DbcValueType::kFloat64;
  EXPECT_FALSE(CompiledSignal::Compile(wrong).ok());
}

TEST(SignalDecoderTest, RefusesImpossibleLayouts) {
  EXPECT_FALSE(CompiledSignal::Compile(Signal(0, 0, true, false)).ok());
  EXPECT_FALSE(CompiledSignal::Compile(Signal(0, 65, true, false)).ok());
  EXPECT_FALSE(CompiledSignal::Compile(Signal(510, 8, true, false)).ok());  // past byte 63
  EXPECT_TRUE(CompiledSignal::Compile(Signal(504, 8, true, false)).ok());
}

// The spec's definition walked bit by bit: Intel goes up from the LSB; Motorola goes down
// from the MSB and jumps from bit 0 of a byte to bit 7 of the next (+15).
std::uint64_t ReferenceRaw(const DbcSignal& signal, const std::vector<std::uint8_t>& payload) {
  std::uint64_t raw = 0;
  std::size_t position = signal.start_bit;
  for (std::size_t i = 0; i < signal.length; ++i) {
    const std::size_t value_bit = signal.little_endian ? i : signal.length - 1 - i;
    const std::uint64_t bit = (payload[position / 8] >> (position % 8)) & 1u;
    raw |= bit << value_bit;
    if (signal.little_endian) {
      ++position;
    } else {
      position = position % 8 == 0 ? position + 15 : position - 1;
    }
  }
  return raw;
}

TEST(SignalDecoderTest, MatchesBitwiseReferenceOnRandomLayouts) {
  const unsigned seed = 42;
  std::mt19937 random(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 5000; ++trial) {
    const bool intel = random() % 2 == 0;
    const auto length = static_cast<std::uint8_t>(1 + random() % 64);
    const auto start = static_cast<std::uint16_t>(random() % (8 * 48));
    const DbcSignal signal = Signal(start, length, intel, false);
    auto compiled = CompiledSignal::Compile(signal);
    ASSERT_TRUE(compiled.ok());
    std::vector<std::uint8_t> payload(64);
    for (auto& value : payload) value = static_cast<std::uint8_t>(byte(random));
    ASSERT_EQ(compiled->Raw(payload), ReferenceRaw(signal, payload))
        << "start " << start << " length " << int{length} << (intel ? " intel" : " motorola");
    // bytes_needed is exact: one byte less is refused.
    payload.resize(compiled->bytes_needed());
    EXPECT_TRUE(compiled->Raw(payload).has_value());
    payload.pop_back();
    EXPECT_FALSE(compiled->Raw(payload).has_value());
  }
}

}  // namespace
}  // namespace flat2d::hal::can
