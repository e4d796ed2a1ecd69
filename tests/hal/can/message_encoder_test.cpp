// Frame building from a DBC message: ids, lengths, checksums (checked by VerifyChecksum and
// against a real RAV4 frame), the rolling counter, multiplexing, error values, and no
// allocation after Create. Real frames: message_encoder_real_data_test.cpp.
#include "hal/can/message_encoder.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::can {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr const char* kDbcText = R"(VERSION ""
BO_ 180 SPEED: 8 XXX
 SG_ ENCODER : 39|8@0+ (1,0) [0|255] "" XXX
 SG_ SPEED : 47|16@0+ (0.01,0) [0|250] "km/h" XXX
 SG_ CHECKSUM : 63|8@0+ (1,0) [0|255] "" XXX
BO_ 2147484106 HONDA_EXT: 8 XXX
 SG_ ACCEL : 7|16@0- (0.0015,0) [-20|20] "m/s2" XXX
 SG_ COUNTER : 61|2@0+ (1,0) [0|3] "" XXX
 SG_ CHECKSUM : 59|4@0+ (1,0) [0|15] "" XXX
BO_ 300 MUXED: 8 XXX
 SG_ MUX M : 0|4@1+ (1,0) [0|15] "" XXX
 SG_ A m1 : 8|8@1+ (1,0) [0|255] "" XXX
 SG_ B m2 : 8|8@1+ (1,0) [0|255] "" XXX
BO_ 301 FD_MSG: 12 XXX
 SG_ TAIL : 88|8@1+ (1,0) [0|255] "" XXX
)";

Dbc TestDbc() {
  Result<Dbc> dbc = ParseDbc(kDbcText, "test.dbc");
  EXPECT_TRUE(dbc.ok()) << (dbc.ok() ? "" : dbc.error().message);
  return dbc.ok() ? *dbc : Dbc{};
}

MessageEncoder Encoder(const Dbc& dbc, const char* name, const MessageEncoderOptions& options = {}) {
  Result<MessageEncoder> encoder = MessageEncoder::Create(dbc, name, options);
  EXPECT_TRUE(encoder.ok()) << (encoder.ok() ? "" : encoder.error().message);
  return std::move(*encoder);
}

Bytes PayloadOf(const CanFrame& frame) { return {frame.payload().begin(), frame.payload().end()}; }

TEST(MessageEncoderTest, ToyotaSpeedFrameMatchesARealFrame) {
  const Dbc dbc = TestDbc();
  MessageEncoder speed = Encoder(dbc, "SPEED");
  EXPECT_EQ(speed.checksum(), ChecksumKind::kToyota);  // detected
  EXPECT_FALSE(speed.has_counter());
  EXPECT_EQ(speed.Set("ENCODER", 29.0), EncodeStatus::kOk);
  EXPECT_EQ(speed.Set("SPEED", 29.38), EncodeStatus::kOk);
  const CanFrame frame = speed.Build(123);
  // Real RAV4 frame 0B4#000000001D0B7A5E (tests/hal/can/checksum_test.cpp).
  EXPECT_EQ(frame.id, 0xB4u);
  EXPECT_FALSE(frame.extended);
  EXPECT_FALSE(frame.fd);
  EXPECT_EQ(frame.time_ns, 123);
  EXPECT_EQ(PayloadOf(frame), (Bytes{0, 0, 0, 0, 0x1D, 0x0B, 0x7A, 0x5E}));
  EXPECT_EQ(Bytes(speed.defined_bits().begin(), speed.defined_bits().end()),
            (Bytes{0, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF}));
}

TEST(MessageEncoderTest, HondaCounterRollsAndChecksumVerifies) {
  const Dbc dbc = TestDbc();
  MessageEncoder honda = Encoder(dbc, "HONDA_EXT");
  EXPECT_EQ(honda.checksum(), ChecksumKind::kHonda);
  ASSERT_TRUE(honda.has_counter());
  EXPECT_EQ(honda.Set("ACCEL", -1.5), EncodeStatus::kOk);  // raw -1000 = 0xFC18
  honda.set_counter(2);
  const std::uint8_t expected_counters[] = {2, 3, 0, 1, 2};
  for (const std::uint8_t counter : expected_counters) {
    const CanFrame frame = honda.Build();
    EXPECT_TRUE(frame.extended);
    EXPECT_EQ(frame.id, 458u);
    EXPECT_EQ(frame.data[0], 0xFC);
    EXPECT_EQ(frame.data[1], 0x18);
    EXPECT_EQ((frame.data[7] >> 4) & 0x3, counter);
    EXPECT_TRUE(VerifyChecksum(ChecksumKind::kHonda, frame));
    CanFrame standard = frame;
    standard.extended = false;  // the +3 for 29-bit ids matters
    EXPECT_FALSE(VerifyChecksum(ChecksumKind::kHonda, standard));
  }
}

TEST(MessageEncoderTest, ExplicitChecksumAndDisabledCounter) {
  const Dbc dbc = TestDbc();
  MessageEncoderOptions options;
  options.checksum = ChecksumKind::kNone;
  options.counter_signal.clear();
  MessageEncoder honda = Encoder(dbc, "HONDA_EXT", options);
  EXPECT_FALSE(honda.has_counter());
  EXPECT_EQ(honda.Set("COUNTER", 3.0), EncodeStatus::kOk);
  EXPECT_EQ(honda.Set("CHECKSUM", 5.0), EncodeStatus::kOk);
  EXPECT_EQ(honda.Build().data[7], 0x35);
  EXPECT_EQ(honda.Build().data[7], 0x35);  // no counter advance
}

TEST(MessageEncoderTest, MultiplexedSignalWritesItsSwitch) {
  const Dbc dbc = TestDbc();
  MessageEncoder muxed = Encoder(dbc, "MUXED");
  EXPECT_EQ(muxed.Set("B", 0x42), EncodeStatus::kOk);
  EXPECT_EQ(PayloadOf(muxed.Build()), (Bytes{0x02, 0x42, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(muxed.Set("A", 0x17), EncodeStatus::kOk);
  EXPECT_EQ(PayloadOf(muxed.Build()), (Bytes{0x01, 0x17, 0, 0, 0, 0, 0, 0}));
}

TEST(MessageEncoderTest, FdLengthComesFromTheDbc) {
  const Dbc dbc = TestDbc();
  MessageEncoder fd = Encoder(dbc, "FD_MSG");
  EXPECT_EQ(fd.Set("TAIL", 7.0), EncodeStatus::kOk);
  const CanFrame frame = fd.Build();
  EXPECT_TRUE(frame.fd);
  EXPECT_EQ(frame.length, 12);
  EXPECT_EQ(frame.data[11], 7);
}

TEST(MessageEncoderTest, ErrorsAreValuesAndCounted) {
  const Dbc dbc = TestDbc();
  EXPECT_FALSE(MessageEncoder::Create(dbc, "NO_SUCH_MESSAGE").ok());
  MessageEncoder speed = Encoder(dbc, "SPEED");
  EXPECT_EQ(speed.Set("NO_SUCH_SIGNAL", 1.0), EncodeStatus::kUnknownSignal);
  EXPECT_EQ(speed.Set(std::size_t{99}, 1.0), EncodeStatus::kUnknownSignal);
  EXPECT_EQ(speed.Set("SPEED", std::nan("")), EncodeStatus::kNotANumber);
  EXPECT_EQ(speed.Set("SPEED", 1e6), EncodeStatus::kClamped);
  EXPECT_EQ(speed.stats().sets, 4u);
  EXPECT_EQ(speed.stats().unknown_signal, 2u);
  EXPECT_EQ(speed.stats().not_a_number, 1u);
  EXPECT_EQ(speed.stats().clamped, 1u);
  EXPECT_EQ(PayloadOf(speed.Build())[5], 0xFF);
  speed.Clear();
  EXPECT_EQ(PayloadOf(speed.Build())[5], 0x00);
}

TEST(MessageEncoderTest, SetAndBuildAllocateNothing) {
  const Dbc dbc = TestDbc();
  MessageEncoder honda = Encoder(dbc, "HONDA_EXT");
  const std::size_t accel = *honda.IndexOf("ACCEL");
  const std::uint64_t before = testing::AllocationCount();
  std::uint32_t sum = 0;
  for (int i = 0; i < 1000; ++i) {
    (void)honda.Set(accel, 0.01 * i);
    (void)honda.Set("ACCEL", -0.01 * i);
    sum += honda.Build(i).data[7];
  }
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_GT(sum, 0u);
}

}  // namespace
}  // namespace flat2d::hal::can
