// Re-encoding real frames: every frame of a message is decoded with all its DBC signals,
// the physical values are encoded into a zeroed frame (checksum and counter by the
// encoder), and the bytes must equal the original's on every bit the DBC defines. Bits no
// signal covers are counted, not compared; seeded with them, the rebuilt frame must be
// identical byte for byte, checksum included. Data: ../shared/data/can (PROVENANCE.md);
// skips when absent.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/can/candump_log.hpp"
#include "hal/can/message_encoder.hpp"
#include "hal/can/signal_decoder.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::can {
namespace {

constexpr const char* kRav4Dbc = "can/toyota_rav4h_comma2k19/toyota_rav4_hybrid_2017_pt_generated.dbc";
constexpr const char* kRav4Log = "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_bus0.candump.log";
constexpr const char* kHondaDbc = "can/eldominio_candump/honda_civic_hatchback_ex_2017_can_generated.dbc";
constexpr const char* kHondaLog = "can/eldominio_candump/civic_19_type_r__turnonanddrive.log";

// Frames closer than this are consecutive for the 100 Hz messages tested: their counters
// must follow each other. The Civic log is decimated, with gaps of seconds.
constexpr TimeNs kMaxCounterGapNs = 15 * kNsPerMs;

std::uint8_t ChecksumBitsOf(ChecksumKind kind) {
  if (kind == ChecksumKind::kToyota) return 0xFF;
  return kind == ChecksumKind::kHonda ? 0x0F : 0x00;
}

struct ReencodeStats {
  std::uint64_t frames = 0;
  std::uint64_t exact_on_defined_bits = 0;
  std::uint64_t identical = 0;            // every byte, defined or not
  std::uint64_t undefined_bits_set = 0;   // frames with a 1 in bits no signal covers
  std::uint64_t counter_resyncs = 0;      // the log skipped frames (a gap of kMaxCounterGapNs+)
  std::uint64_t counter_breaks = 0;       // the counter skipped a value between close frames
  std::uint64_t checksum_valid = 0;       // of the original frames
};

// Re-encodes every frame of `message` in `log`. With the encoder's rolling counter, the
// counter is seeded from the first frame and resynchronised (and counted) on gaps.
ReencodeStats Reencode(const Dbc& dbc, const std::filesystem::path& log, const std::string& message,
                       const MessageEncoderOptions& options) {
  ReencodeStats stats;
  const DbcMessage* definition = dbc.FindMessage(message);
  Result<MessageEncoder> encoder = MessageEncoder::Create(dbc, message, options);
  Result<CandumpReader> reader = CandumpReader::Open(log);
  EXPECT_TRUE(definition != nullptr && encoder.ok() && reader.ok()) << message;
  if (definition == nullptr || !encoder.ok() || !reader.ok()) return stats;
  std::vector<CompiledSignal> decoders;
  for (const DbcSignal& signal : definition->signals) decoders.push_back(*CompiledSignal::Compile(signal));
  CanFrame original;
  TimeNs previous_ns = 0;
  while (reader->Next(original)) {
    if (original.id != definition->id || original.extended != definition->extended) continue;
    ++stats.frames;
    stats.checksum_valid += VerifyChecksum(encoder->checksum(), original) ? 1 : 0;
    encoder->Clear();
    for (std::size_t i = 0; i < decoders.size(); ++i) {
      const double value = *decoders[i].Decode(original.payload());
      if (encoder->has_counter() && definition->signals[i].name == options.counter_signal) {
        const auto counter = static_cast<std::uint64_t>(value);
        const bool close = original.time_ns - previous_ns < kMaxCounterGapNs;
        if (stats.frames > 1 && encoder->counter() != counter) {
          ++(close ? stats.counter_breaks : stats.counter_resyncs);
        }
        encoder->set_counter(counter);
        continue;
      }
      EXPECT_EQ(encoder->Set(i, value), EncodeStatus::kOk) << message << " " << definition->signals[i].name;
    }
    const CanFrame built = encoder->Build(original.time_ns);
    EXPECT_EQ(built.length, original.length);
    EXPECT_TRUE(VerifyChecksum(encoder->checksum(), built)) << message;
    bool undefined_set = false;
    bool identical = true;
    for (std::size_t b = 0; b < built.length; ++b) {
      undefined_set = undefined_set || (original.data[b] & ~encoder->defined_bits()[b]) != 0;
      identical = identical && built.data[b] == original.data[b];
    }
    // The checksum covers the undefined bits the zeroed frame lacks: skip it then.
    const std::uint8_t checksum_bits = ChecksumBitsOf(encoder->checksum());
    bool exact = true;
    for (std::size_t b = 0; b < built.length; ++b) {
      std::uint8_t compared = encoder->defined_bits()[b];
      if (undefined_set && b + 1 == built.length) compared = static_cast<std::uint8_t>(compared & ~checksum_bits);
      exact = exact && (built.data[b] & compared) == (original.data[b] & compared);
    }
    // Seeded with the original's undefined bits, the rebuilt frame is identical, checksum too.
    std::array<std::uint8_t, kMaxFdDataBytes> undefined{};
    for (std::size_t b = 0; b < built.length; ++b) {
      undefined[b] = static_cast<std::uint8_t>(original.data[b] & ~encoder->defined_bits()[b]);
    }
    if (encoder->has_counter()) encoder->set_counter(encoder->counter() - 1);  // Build advanced it
    encoder->SetPayload(undefined);
    for (std::size_t i = 0; i < decoders.size(); ++i) {
      if (!(encoder->has_counter() && definition->signals[i].name == options.counter_signal)) {
        (void)encoder->Set(i, *decoders[i].Decode(original.payload()));
      }
    }
    const CanFrame seeded = encoder->Build(original.time_ns);
    EXPECT_TRUE(std::equal(seeded.data.begin(), seeded.data.begin() + original.length, original.data.begin()))
        << message << " frame " << stats.frames;
    EXPECT_TRUE(exact) << message << " frame " << stats.frames << " at " << original.time_ns;
    stats.exact_on_defined_bits += exact ? 1 : 0;
    stats.undefined_bits_set += undefined_set ? 1 : 0;
    stats.identical += identical ? 1 : 0;
    previous_ns = original.time_ns;
  }
  std::printf("%s: %llu frames, %llu exact on defined bits, %llu identical, %llu with undefined bits set, "
              "%llu checksums valid, %llu counter resyncs after gaps, %llu counter breaks\n",
              message.c_str(), static_cast<unsigned long long>(stats.frames),
              static_cast<unsigned long long>(stats.exact_on_defined_bits),
              static_cast<unsigned long long>(stats.identical),
              static_cast<unsigned long long>(stats.undefined_bits_set),
              static_cast<unsigned long long>(stats.checksum_valid),
              static_cast<unsigned long long>(stats.counter_resyncs),
              static_cast<unsigned long long>(stats.counter_breaks));
  return stats;
}

MessageEncoderOptions WithChecksum(std::optional<ChecksumKind> kind) {
  MessageEncoderOptions options;
  options.checksum = kind;
  return options;
}

TEST(MessageEncoderRealDataTest, Rav4FramesReencodeByteExact) {
  FLAT2D_REQUIRE_DATA(dbc_path, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log_path, kRav4Log);
  Result<Dbc> dbc = LoadDbc(dbc_path);
  ASSERT_TRUE(dbc.ok()) << dbc.error().message;
  struct Case {
    const char* message;
    std::optional<ChecksumKind> checksum;  // nullopt: detected from the DBC
    ChecksumKind expected;
  };
  // 0x24 and 0x25 carry a Toyota checksum their DBC entries do not name.
  const Case cases[] = {{"WHEEL_SPEEDS", std::nullopt, ChecksumKind::kNone},
                        {"SPEED", std::nullopt, ChecksumKind::kToyota},
                        {"KINEMATICS", ChecksumKind::kToyota, ChecksumKind::kToyota},
                        {"STEER_ANGLE_SENSOR", ChecksumKind::kToyota, ChecksumKind::kToyota}};
  for (const Case& c : cases) {
    const ReencodeStats stats = Reencode(*dbc, log_path, c.message, WithChecksum(c.checksum));
    ASSERT_GT(stats.frames, 100u) << c.message;
    EXPECT_EQ(stats.exact_on_defined_bits, stats.frames) << c.message;
    EXPECT_EQ(stats.identical + stats.undefined_bits_set, stats.frames) << c.message;
    if (c.expected != ChecksumKind::kNone) {
      EXPECT_EQ(stats.checksum_valid, stats.frames) << c.message;
    }
  }
}

TEST(MessageEncoderRealDataTest, CivicFramesReencodeWithChecksumAndCounter) {
  FLAT2D_REQUIRE_DATA(dbc_path, kHondaDbc);
  FLAT2D_REQUIRE_DATA(log_path, kHondaLog);
  Result<Dbc> dbc = LoadDbc(dbc_path);
  ASSERT_TRUE(dbc.ok()) << dbc.error().message;
  // WHEEL_SPEEDS 0x1D0: four 15-bit speeds and the Honda checksum cover all 64 bits; its
  // DBC entry names no COUNTER. VEHICLE_DYNAMICS 0x1EA has both, so it tests the counter.
  for (const char* message : {"WHEEL_SPEEDS", "VEHICLE_DYNAMICS"}) {
    const ReencodeStats stats = Reencode(*dbc, log_path, message, WithChecksum(std::nullopt));
    ASSERT_GT(stats.frames, 100u) << message;
    EXPECT_EQ(stats.exact_on_defined_bits, stats.frames) << message;
    EXPECT_EQ(stats.checksum_valid, stats.frames) << message;
    EXPECT_EQ(stats.counter_breaks, 0u) << message;
  }
}

}  // namespace
}  // namespace flat2d::hal::can
