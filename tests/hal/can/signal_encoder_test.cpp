// Signal encoding against frames computed by hand from the DBC bit numbering (Vector DBC
// spec: Intel start = LSB, Motorola start = MSB in the sawtooth numbering), clamping at
// the ends of the bit range, and decode(encode(x)) == x within half a step on seeded
// random layouts, checked against the decoder and an independent bit-by-bit reference.
#include "hal/can/signal_encoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/hal/can/test_signal.hpp"

#include "hal/can/signal_decoder.hpp"

namespace flat2d::hal::can {
namespace {

using Bytes = std::vector<std::uint8_t>;

using test::Signal;

CompiledSignalEncoder Compile(const DbcSignal& signal) {
  auto compiled = CompiledSignalEncoder::Compile(signal);
  EXPECT_TRUE(compiled.ok()) << (compiled.ok() ? "" : compiled.error().message);
  return compiled.ok() ? *compiled : CompiledSignalEncoder{};
}

// Encodes `physical` into `payload` (filled with `fill`), expecting `status`.
Bytes Encoded(const DbcSignal& signal, double physical, std::uint8_t fill = 0x00,
              EncodeStatus status = EncodeStatus::kOk) {
  Bytes payload(8, fill);
  EXPECT_EQ(Compile(signal).Encode(payload, physical), status) << "physical " << physical;
  return payload;
}

TEST(SignalEncoderTest, IntelAcrossBytesLeavesOtherBitsAlone) {
  // 4|12@1+: LSB at bit 4 of byte 0; 0xABC -> byte 0 high nibble C, byte 1 = AB.
  EXPECT_EQ(Encoded(Signal(4, 12, true, false), 0xABC, 0xFF), (Bytes{0xCF, 0xAB, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(Encoded(Signal(4, 12, true, false), 0xABC, 0x00), (Bytes{0xC0, 0xAB, 0, 0, 0, 0, 0, 0}));
}

TEST(SignalEncoderTest, MotorolaSawtoothAcrossThreeBytes) {
  // 2|12@0+: MSB at bit 2 of byte 0 (lin 5), LSB at lin 16 = bit 7 of byte 2.
  // 0xABD = 101 | 0101 1110 | 1 -> byte 0 bits 2..0 = 101, byte 1 = 0x5E, byte 2 bit 7 = 1.
  EXPECT_EQ(Encoded(Signal(2, 12, false, false), 0xABD), (Bytes{0x05, 0x5E, 0x80, 0, 0, 0, 0, 0}));
  EXPECT_EQ(Encoded(Signal(2, 12, false, false), 0xABC, 0xFF),
            (Bytes{0xFD, 0x5E, 0x7F, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
}

TEST(SignalEncoderTest, RealToyotaLayoutsByHand) {
  // RAV4 WHEEL_SPEED_FR 7|16@0+ (0.01,-67.67): 10 km/h -> raw 7767 = 0x1E57, big-endian.
  EXPECT_EQ(Encoded(Signal(7, 16, false, false, 0.01, -67.67), 10.0), (Bytes{0x1E, 0x57, 0, 0, 0, 0, 0, 0}));
  // RAV4 STEER_ANGLE 3|12@0- (1.5,0): -3 deg -> raw -2 = 0xFFE: byte 0 low nibble F, byte 1 FE.
  EXPECT_EQ(Encoded(Signal(3, 12, false, true, 1.5), -3.0), (Bytes{0x0F, 0xFE, 0, 0, 0, 0, 0, 0}));
  // The same value in Intel order at 52|12@1-: bits 52..63 -> byte 6 high nibble E, byte 7 FF.
  EXPECT_EQ(Encoded(Signal(52, 12, true, true, 1.5), -3.0), (Bytes{0, 0, 0, 0, 0, 0, 0xE0, 0xFF}));
}

TEST(SignalEncoderTest, OneBitSignalsInBothOrders) {
  for (const bool intel : {true, false}) {
    // Bit 13 is bit 5 of byte 1 in both orders.
    EXPECT_EQ(Encoded(Signal(13, 1, intel, false), 1.0), (Bytes{0, 0x20, 0, 0, 0, 0, 0, 0})) << intel;
    EXPECT_EQ(Encoded(Signal(13, 1, intel, false), 0.0, 0xFF),
              (Bytes{0xFF, 0xDF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}))
        << intel;
    Encoded(Signal(13, 1, intel, false), 2.0, 0x00, EncodeStatus::kClamped);
  }
}

TEST(SignalEncoderTest, SixtyFourBitSignals) {
  // 2^63 + 2^11 is exact in a double.
  EXPECT_EQ(Encoded(Signal(0, 64, true, false), 9223372036854777856.0),
            (Bytes{0x00, 0x08, 0, 0, 0, 0, 0, 0x80}));
  EXPECT_EQ(Encoded(Signal(7, 64, false, false), 9223372036854777856.0),
            (Bytes{0x80, 0, 0, 0, 0, 0, 0x08, 0x00}));
  EXPECT_EQ(Encoded(Signal(0, 64, true, true), -1.0), Bytes(8, 0xFF));
  EXPECT_EQ(Encoded(Signal(0, 64, true, true), -9223372036854775808.0), (Bytes{0, 0, 0, 0, 0, 0, 0, 0x80}));
  EXPECT_EQ(Encoded(Signal(0, 64, true, true), 1e30, 0, EncodeStatus::kClamped),
            (Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F}));
  EXPECT_EQ(Encoded(Signal(0, 64, true, false), 1e30, 0, EncodeStatus::kClamped), Bytes(8, 0xFF));
  // Raw bits beyond a double's precision: WriteRaw, read back by the decoder.
  const DbcSignal motorola = Signal(7, 64, false, false);
  Bytes payload(8, 0);
  ASSERT_TRUE(Compile(motorola).WriteRaw(payload, 0x0123456789ABCDEFull));
  EXPECT_EQ(payload, (Bytes{0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF}));
  EXPECT_EQ(CompiledSignal::Compile(motorola)->Raw(payload), 0x0123456789ABCDEFull);
}

TEST(SignalEncoderTest, ClampsToTheBitRangeAndSaysSo) {
  const DbcSignal u8 = Signal(7, 8, false, false);
  EXPECT_EQ(Encoded(u8, 255.4)[0], 0xFF);
  EXPECT_EQ(Encoded(u8, 255.6, 0, EncodeStatus::kClamped)[0], 0xFF);
  EXPECT_EQ(Encoded(u8, -0.4)[0], 0x00);
  EXPECT_EQ(Encoded(u8, -0.6, 0xAA, EncodeStatus::kClamped)[0], 0x00);
  EXPECT_EQ(Encoded(u8, std::numeric_limits<double>::infinity(), 0, EncodeStatus::kClamped)[0], 0xFF);
  const DbcSignal s8 = Signal(7, 8, false, true);
  EXPECT_EQ(Encoded(s8, -128.4)[0], 0x80);
  EXPECT_EQ(Encoded(s8, -128.6, 0, EncodeStatus::kClamped)[0], 0x80);
  EXPECT_EQ(Encoded(s8, 127.6, 0, EncodeStatus::kClamped)[0], 0x7F);
  EXPECT_EQ(Encoded(s8, -1.0)[0], 0xFF);
  // Offset and factor apply before the clamp: (physical + 67.67) / 0.01 must fit 16 bits.
  const DbcSignal wheel = Signal(7, 16, false, false, 0.01, -67.67);
  EXPECT_EQ(Encoded(wheel, -67.67)[0], 0x00);
  EXPECT_EQ(Encoded(wheel, -70.0, 0xFF, EncodeStatus::kClamped)[0], 0x00);
  EXPECT_EQ(Encoded(wheel, 600.0, 0, EncodeStatus::kClamped)[1], 0xFF);
}

TEST(SignalEncoderTest, NaNAndShortPayloadsWriteNothing) {
  const CompiledSignalEncoder encoder = Compile(Signal(7, 16, false, false, 0.01, -67.67));
  Bytes payload(8, 0xA5);
  EXPECT_EQ(encoder.Encode(payload, std::nan("")), EncodeStatus::kNotANumber);
  EXPECT_EQ(payload, Bytes(8, 0xA5));
  Bytes short_payload(1, 0xA5);
  EXPECT_EQ(encoder.Encode(short_payload, 1.0), EncodeStatus::kTooShort);
  EXPECT_FALSE(encoder.WriteRaw(short_payload, 1));
  EXPECT_EQ(short_payload[0], 0xA5);
}

TEST(SignalEncoderTest, IeeeFloatIsBitCast) {
  DbcSignal signal = Signal(0, 32, true, false);
  signal.value_type = DbcValueType::kFloat32;
  EXPECT_EQ(Encoded(signal, 1.5), (Bytes{0x00, 0x00, 0xC0, 0x3F, 0, 0, 0, 0}));
  Encoded(signal, 1e300, 0, EncodeStatus::kClamped);
}

TEST(SignalEncoderTest, RefusesSignalsWithoutAnInverse) {
  EXPECT_FALSE(CompiledSignalEncoder::Compile(Signal(0, 8, true, false, 0.0)).ok());
  EXPECT_FALSE(CompiledSignalEncoder::Compile(Signal(0, 8, true, false, std::nan(""))).ok());
  EXPECT_FALSE(CompiledSignalEncoder::Compile(Signal(0, 0, true, false)).ok());
  EXPECT_FALSE(CompiledSignalEncoder::Compile(Signal(0, 65, true, false)).ok());
  EXPECT_FALSE(CompiledSignalEncoder::Compile(Signal(511, 16, true, false)).ok());  // past 64 bytes
}

// Independent reference: byte and bit of value bit k, walking the sawtooth one bit at a time.
std::pair<std::size_t, std::size_t> ReferencePlace(const DbcSignal& signal, std::size_t k) {
  std::size_t bit = signal.start_bit;
  if (signal.little_endian) return {(bit + k) / 8, (bit + k) % 8};
  for (std::size_t step = 0; step + 1 + k < signal.length; ++step) bit = bit % 8 == 0 ? bit + 15 : bit - 1;
  return {bit / 8, bit % 8};
}

// A random layout that fits 8 bytes (64 for one case in 8, CAN FD).
DbcSignal RandomSignal(std::mt19937& rng) {
  const bool fd = std::uniform_int_distribution<int>(0, 7)(rng) == 0;
  const std::size_t bits = fd ? 512 : 64;
  const auto length = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(1, 64)(rng));
  const bool intel = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
  // Pick the LSB's linear position so the signal fits, then convert to the start bit.
  const std::size_t first = std::uniform_int_distribution<std::size_t>(0, bits - length)(rng);
  std::uint16_t start = 0;
  if (intel) {
    start = static_cast<std::uint16_t>(first);
  } else {
    start = static_cast<std::uint16_t>(8 * (first / 8) + 7 - first % 8);  // first = MSB's lin
  }
  double factor = std::uniform_real_distribution<double>(0.001, 10.0)(rng);
  if (std::uniform_int_distribution<int>(0, 3)(rng) == 0) factor = -factor;
  const double offset = std::uniform_real_distribution<double>(-1e4, 1e4)(rng);
  return Signal(start, length, intel, std::uniform_int_distribution<int>(0, 1)(rng) == 1, factor, offset);
}

TEST(SignalEncoderTest, DecodeOfEncodeIsIdentityOnRandomLayouts) {
  constexpr std::uint32_t seed = 20240501;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 3000; ++trial) {
    const DbcSignal signal = RandomSignal(rng);
    const CompiledSignalEncoder encoder = Compile(signal);
    const auto decoder = CompiledSignal::Compile(signal);
    ASSERT_TRUE(decoder.ok());
    // A raw value far inside a double's 53-bit mantissa, so the jitter stays resolvable.
    const int bits = std::min<int>(signal.length, 40);
    const double top = std::ldexp(1.0, signal.is_signed ? bits - 1 : bits);
    const double raw = std::floor(std::uniform_real_distribution<double>(signal.is_signed ? -top : 0.0, top)(rng));
    const double jitter = std::uniform_real_distribution<double>(-0.45, 0.45)(rng);
    const double physical = (raw + jitter) * signal.factor + signal.offset;
    Bytes payload(encoder.bytes_needed());
    for (std::uint8_t& byte : payload) byte = static_cast<std::uint8_t>(rng());
    const Bytes before = payload;
    ASSERT_EQ(encoder.Encode(payload, physical), EncodeStatus::kOk) << "seed " << seed << " trial " << trial;
    const double decoded = *decoder->Decode(payload);
    const double tolerance = 0.5 * std::fabs(signal.factor) + 1e-9 * std::fabs(physical) + 1e-9;
    EXPECT_NEAR(decoded, physical, tolerance) << "seed " << seed << " trial " << trial << " start "
                                              << signal.start_bit << " length " << int{signal.length};
    // Every bit outside the signal is untouched; every bit inside holds the raw value.
    Bytes mask(payload.size(), 0);
    const std::uint64_t expected_raw = encoder.ToRaw(physical).raw;
    for (std::size_t k = 0; k < signal.length; ++k) {
      const auto [byte, bit] = ReferencePlace(signal, k);
      mask[byte] = static_cast<std::uint8_t>(mask[byte] | (1u << bit));
      EXPECT_EQ((payload[byte] >> bit) & 1u, (expected_raw >> k) & 1u) << "seed " << seed << " trial " << trial;
    }
    for (std::size_t i = 0; i < payload.size(); ++i) {
      ASSERT_EQ(payload[i] & ~mask[i], before[i] & ~mask[i]) << "seed " << seed << " trial " << trial;
    }
  }
}

}  // namespace
}  // namespace flat2d::hal::can
