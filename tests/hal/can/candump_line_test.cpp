// Every candump -l line form, parsed from hand-written text and formatted back.
#include "hal/can/candump_line.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>
#include <vector>

namespace flat2d::hal::can {
namespace {

struct Parsed {
  CandumpLine line;
  CanFrame frame;
};

Parsed Parse(std::string_view text) {
  Parsed parsed;
  parsed.line = ParseCandumpLine(text, parsed.frame);
  return parsed;
}

std::vector<std::uint8_t> Payload(const CanFrame& frame) {
  return {frame.payload().begin(), frame.payload().end()};
}

std::string Format(const CanFrame& frame, const CandumpFormat& format = {},
                   CandumpDirection direction = CandumpDirection::kUnknown) {
  std::array<char, kMaxCandumpFormattedBytes> out{};
  const CandumpFormatted formatted = FormatCandumpLine(frame, format, direction, out);
  EXPECT_TRUE(formatted.error.empty()) << formatted.error;
  return {out.data(), formatted.size};
}

std::string FormatError(const CanFrame& frame) {
  std::array<char, kMaxCandumpFormattedBytes> out{};
  const CandumpFormatted formatted = FormatCandumpLine(frame, {}, CandumpDirection::kUnknown, out);
  EXPECT_EQ(formatted.size, 0u);
  return std::string(formatted.error);
}

TEST(CandumpLine, StandardFrameWithExactTime) {
  const Parsed p = Parse("(1674148739.212264) can0 112#FF0015");
  ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame) << DescribeCandumpError(p.line.error);
  EXPECT_EQ(p.frame.time_ns, 1'674'148'739'212'264'000);
  EXPECT_EQ(p.frame.interface_name(), "can0");
  EXPECT_EQ(p.frame.id, 0x112u);
  EXPECT_FALSE(p.frame.extended || p.frame.remote || p.frame.error || p.frame.fd);
  EXPECT_EQ(Payload(p.frame), (std::vector<std::uint8_t>{0xFF, 0x00, 0x15}));
  EXPECT_EQ(p.line.direction, CandumpDirection::kUnknown);
}

TEST(CandumpLine, TimesAreExactToTheNanosecond) {
  EXPECT_EQ(Parse("(46408.584930) can0 0B4#00").frame.time_ns, 46'408'584'930'000);
  EXPECT_EQ(Parse("(1.5) can0 0B4#00").frame.time_ns, 1'500'000'000);
  EXPECT_EQ(Parse("(0.000000001) can0 0B4#00").frame.time_ns, 1);
  EXPECT_EQ(Parse("(0000000000.000000) can0 0B4#00").frame.time_ns, 0);
  // The largest time whose nanoseconds fit in int64 with a full fraction.
  EXPECT_EQ(Parse("(9223372035.999999999) can0 0B4#00").frame.time_ns, 9'223'372'035'999'999'999);
}

TEST(CandumpLine, ExtendedIds) {
  const Parsed p = Parse("(1.000000) can1 1ABCDEF0#0102030405060708");
  ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame);
  EXPECT_TRUE(p.frame.extended);
  EXPECT_EQ(p.frame.id, 0x1ABCDEF0u);
  EXPECT_EQ(Payload(p.frame), (std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8}));
  // 8 digits make an extended frame even when the value would fit in 11 bits.
  const Parsed small = Parse("(1.000000) can1 00000123#");
  EXPECT_TRUE(small.frame.extended);
  EXPECT_EQ(small.frame.id, 0x123u);
  EXPECT_EQ(small.frame.length, 0);
}

TEST(CandumpLine, RemoteFrames) {
  const Parsed bare = Parse("(1.000000) can0 123#R");
  ASSERT_EQ(bare.line.kind, CandumpLineKind::kFrame);
  EXPECT_TRUE(bare.frame.remote);
  EXPECT_EQ(bare.frame.length, 0);
  const Parsed with_dlc = Parse("(1.000000) can0 123#R5");
  EXPECT_TRUE(with_dlc.frame.remote);
  EXPECT_EQ(with_dlc.frame.length, 5);
  EXPECT_TRUE(with_dlc.frame.payload().empty());  // a request carries no data
  const Parsed extended = Parse("(1.000000) can0 1FFFFFFF#r8");
  EXPECT_TRUE(extended.frame.remote && extended.frame.extended);
  EXPECT_EQ(extended.frame.id, 0x1FFFFFFFu);
  EXPECT_EQ(extended.frame.length, 8);
  EXPECT_EQ(Parse("(1.000000) can0 123#R8_C").line.kind, CandumpLineKind::kFrame);
}

TEST(CandumpLine, CanFdFrames) {
  const Parsed p = Parse("(1.000000) can0 123##1112233445566778899AABBCC");
  ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame) << DescribeCandumpError(p.line.error);
  EXPECT_TRUE(p.frame.fd);
  EXPECT_EQ(p.frame.fd_flags, 0x1);
  EXPECT_EQ(p.frame.length, 12);
  EXPECT_EQ(p.frame.data[0], 0x11);
  EXPECT_EQ(p.frame.data[11], 0xCC);
  const Parsed empty = Parse("(1.000000) can0 123##0");
  EXPECT_TRUE(empty.frame.fd);
  EXPECT_EQ(empty.frame.length, 0);
  const Parsed full = Parse(std::string("(1.000000) can0 12345678##5").append(128, 'E'));
  ASSERT_EQ(full.line.kind, CandumpLineKind::kFrame);
  EXPECT_TRUE(full.frame.extended && full.frame.fd);
  EXPECT_EQ(full.frame.fd_flags, 0x5);  // newer candump prints CANFD_FDF (0x04) as well
  EXPECT_EQ(full.frame.length, 64);
  EXPECT_EQ(full.frame.data[63], 0xEE);
}

TEST(CandumpLine, ErrorFramesCarryTheClassInTheId) {
  const Parsed p = Parse("(1.000000) can0 20000080#0000000000000000");
  ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame);
  EXPECT_TRUE(p.frame.error);
  EXPECT_FALSE(p.frame.extended);
  EXPECT_EQ(p.frame.id, 0x80u);  // CAN_ERR_BUSERROR
  EXPECT_EQ(p.frame.length, 8);
  const Parsed controller = Parse("(1.000000) can0 20000004#0004000000000000");
  EXPECT_EQ(controller.frame.id, 0x4u);
  EXPECT_EQ(controller.frame.data[1], 0x04);
}

TEST(CandumpLine, DirectionMarkersSpacingAndCase) {
  EXPECT_EQ(Parse("(1.000000) can0 123#11 T").line.direction, CandumpDirection::kTransmitted);
  EXPECT_EQ(Parse("(1.000000) can0 123#11 R").line.direction, CandumpDirection::kReceived);
  const Parsed remote_rx = Parse("(1.000000) can0 123#R R");
  EXPECT_TRUE(remote_rx.frame.remote);
  EXPECT_EQ(remote_rx.line.direction, CandumpDirection::kReceived);
  // candump pads names to the longest interface; CRLF files; tabs; lowercase hex; dots.
  EXPECT_EQ(Parse("(1.000000)   can0 123#11").frame.interface_name(), "can0");
  EXPECT_EQ(Parse("(1.000000) can0 123#11\r").line.kind, CandumpLineKind::kFrame);
  EXPECT_EQ(Parse("  (1.000000)\tvcan10\t123#11  ").frame.interface_name(), "vcan10");
  EXPECT_EQ(Payload(Parse("(1.000000) can0 7ff#abcdef").frame),
            (std::vector<std::uint8_t>{0xAB, 0xCD, 0xEF}));
  EXPECT_EQ(Parse("(1.000000) can0 7ff#abcdef").frame.id, 0x7FFu);
  EXPECT_EQ(Payload(Parse("(1.000000) can0 123#11.22.33").frame),
            (std::vector<std::uint8_t>{0x11, 0x22, 0x33}));
  EXPECT_EQ(Parse("(1.000000) can0 123#1122334455667788_9").frame.length, 8);
}

TEST(CandumpLine, BlankCommentsAndDropNotices) {
  EXPECT_EQ(Parse("").line.kind, CandumpLineKind::kIgnored);
  EXPECT_EQ(Parse("  \t\r").line.kind, CandumpLineKind::kIgnored);
  EXPECT_EQ(Parse("# recorded on the test track").line.kind, CandumpLineKind::kIgnored);
  EXPECT_EQ(Parse("DROPCOUNT: dropped 3 CAN frames on 'can0' socket (total drops 3)").line.kind,
            CandumpLineKind::kDropNotice);
}

struct MalformedCase {
  std::string line;
  CandumpError error;
};

TEST(CandumpLine, MalformedLinesSayWhy) {
  const std::string fd_9_bytes = std::string("(1.000000) can0 123##0").append(18, '0');
  const std::string fd_65_bytes = std::string("(1.000000) can0 123##0").append(130, '0');
  const std::vector<MalformedCase> cases = {
      {"can0 123#11", CandumpError::kNoTimestamp},
      {"garbage", CandumpError::kNoTimestamp},
      {"(12.34 can0 123#11", CandumpError::kBadTimestamp},
      {"(12) can0 123#11", CandumpError::kBadTimestamp},
      {"(12.) can0 123#11", CandumpError::kBadTimestamp},
      {"(.5) can0 123#11", CandumpError::kBadTimestamp},
      {"(1.1234567890) can0 123#11", CandumpError::kBadTimestamp},
      {"(1a.5) can0 123#11", CandumpError::kBadTimestamp},
      {"(-1.000000) can0 123#11", CandumpError::kBadTimestamp},
      {"(9223372036.000000) can0 123#11", CandumpError::kBadTimestamp},  // overflows int64 ns
      {"(1.000000)can0 123#11", CandumpError::kBadTimestamp},
      {"(1.000000)", CandumpError::kNoInterface},
      {"(1.000000) abcdefghijklmnop 123#11", CandumpError::kInterfaceTooLong},
      {"(1.000000) can0", CandumpError::kNoFrame},
      {"(1.000000) can0 12#11", CandumpError::kBadIdLength},
      {"(1.000000) can0 1234#11", CandumpError::kBadIdLength},
      {"(1.000000) can0 123", CandumpError::kBadIdLength},
      {"(1.000000) can0 12G#11", CandumpError::kBadIdHex},
      {"(1.000000) can0 800#11", CandumpError::kStandardIdTooLarge},
      {"(1.000000) can0 FFF#11", CandumpError::kStandardIdTooLarge},
      {"(1.000000) can0 40000000#11", CandumpError::kExtendedIdTooLarge},
      {"(1.000000) can0 80000123#11", CandumpError::kExtendedIdTooLarge},
      {"(1.000000) can0 20000004#R", CandumpError::kErrorFrameForm},
      {"(1.000000) can0 20000004##000", CandumpError::kErrorFrameForm},
      {"(1.000000) can0 60000004#00", CandumpError::kErrorFrameForm},
      {"(1.000000) can0 123#R9", CandumpError::kBadRemote},
      {"(1.000000) can0 123#RX", CandumpError::kBadRemote},
      {"(1.000000) can0 123#R55", CandumpError::kBadRemote},
      {"(1.000000) can0 123#R5_9", CandumpError::kBadRemote},
      {"(1.000000) can0 123##", CandumpError::kBadFdFlags},
      {"(1.000000) can0 123##G00", CandumpError::kBadFdFlags},
      {"(1.000000) can0 123#11G2", CandumpError::kBadDataHex},
      {"(1.000000) can0 123#1G", CandumpError::kBadDataHex},
      {"(1.000000) can0 123#1122334455667788_5", CandumpError::kBadDataHex},
      {"(1.000000) can0 123##01G", CandumpError::kBadDataHex},
      {"(1.000000) can0 123#112", CandumpError::kOddDataDigits},
      {"(1.000000) can0 123#1.22", CandumpError::kOddDataDigits},
      {"(1.000000) can0 123#112233445566778899", CandumpError::kClassicDataTooLong},
      {fd_9_bytes, CandumpError::kInvalidFdLength},
      {fd_65_bytes, CandumpError::kFdDataTooLong},
      {"(1.000000) can0 123#11 X", CandumpError::kTrailingText},
      {"(1.000000) can0 123#11 T extra", CandumpError::kTrailingText},
      {"(1.000000) can0 123#11 RR", CandumpError::kTrailingText},
  };
  for (const MalformedCase& c : cases) {
    const Parsed p = Parse(c.line);
    EXPECT_EQ(p.line.kind, CandumpLineKind::kMalformed) << c.line;
    EXPECT_EQ(p.line.error, c.error) << c.line << ": got '" << DescribeCandumpError(p.line.error)
                                     << "', expected '" << DescribeCandumpError(c.error) << "'";
  }
}

TEST(CandumpFormat, WritesWhatCandumpWrites) {
  const std::vector<std::string> lines = {
      "(1674148739.212264) can0 112#FF0015\n",
      "(0000000001.000000) can1 1ABCDEF0#0102030405060708\n",
      "(0000000001.000000) can0 00000123#\n",
      "(0000000001.000000) can0 123#R\n",
      "(0000000001.000000) can0 123#R5\n",
      "(0000000001.000000) can0 123##1112233445566778899AABBCC\n",
      "(0000000001.000000) can0 123##4\n",
      "(0000000001.000000) can0 20000080#0000000000000000\n",
      "(0000000001.000000) vcan10 7FF#00 T\n",
      "(0000000001.000000) can0 7FF#01 R\n",
  };
  for (const std::string& line : lines) {
    const Parsed p = Parse(std::string_view(line).substr(0, line.size() - 1));
    ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame) << line;
    EXPECT_EQ(Format(p.frame, {}, p.line.direction), line);
  }
}

TEST(CandumpFormat, PaddingTruncationAndFallbackName) {
  CanFrame frame;
  frame.time_ns = 46'408'584'930'999;  // sub-microsecond part is truncated, as timeval is
  frame.id = 0x260;
  frame.length = 1;
  frame.data[0] = 0x08;
  EXPECT_EQ(Format(frame), "(0000046408.584930) can0 260#08\n");
  EXPECT_EQ(Format(frame, {.seconds_digits = 0}), "(46408.584930) can0 260#08\n");
  frame.set_interface_name("can1");
  EXPECT_EQ(Format(frame, {.seconds_digits = 0, .interface_width = 6}),
            "(46408.584930)   can1 260#08\n");
}

TEST(CandumpFormat, RefusesFramesCandumpCannotHaveWritten) {
  CanFrame frame;
  frame.time_ns = -1;
  EXPECT_NE(FormatError(frame).find("before zero"), std::string::npos);
  frame.time_ns = 0;
  frame.id = 0x800;
  EXPECT_NE(FormatError(frame).find("0x7FF"), std::string::npos);
  frame.extended = true;
  frame.id = 0x20000000;
  EXPECT_NE(FormatError(frame).find("0x1FFFFFFF"), std::string::npos);
  frame = CanFrame{};
  frame.length = 9;
  EXPECT_NE(FormatError(frame).find("8 bytes"), std::string::npos);
  frame.fd = true;
  EXPECT_NE(FormatError(frame).find("DLC"), std::string::npos);
  frame.length = 12;
  frame.remote = true;
  EXPECT_NE(FormatError(frame).find("remote"), std::string::npos);
  frame = CanFrame{};
  frame.error = true;
  frame.remote = true;
  EXPECT_NE(FormatError(frame).find("classic data"), std::string::npos);
  std::array<char, 10> tiny{};
  EXPECT_EQ(FormatCandumpLine(CanFrame{}, {}, CandumpDirection::kUnknown, tiny).size, 0u);
}

// Seeded random frames of every kind survive format -> parse unchanged.
TEST(CandumpFormat, RandomFramesRoundTrip) {
  constexpr unsigned kSeed = 42;
  std::mt19937 random(kSeed);
  std::array<char, kMaxCandumpFormattedBytes> out{};
  for (int i = 0; i < 2000; ++i) {
    CanFrame frame;
    // Unix times up to 2033, in whole microseconds as candump writes them.
    frame.time_ns = static_cast<TimeNs>(random() % 2'000'000'000u) * kNsPerSecond +
                    static_cast<TimeNs>(random() % 1'000'000u) * kNsPerUs;
    frame.set_interface_name(i % 3 == 0 ? "can0" : "vcan12");
    const unsigned kind = random() % 4;
    frame.extended = random() % 2 == 0;
    frame.id = static_cast<std::uint32_t>(random()) &
               (frame.extended ? kMaxExtendedId : kMaxStandardId);
    const auto draw = [&](unsigned below) { return static_cast<std::uint8_t>(random() % below); };
    if (kind == 0) {
      frame.remote = true;
      frame.length = draw(9);
    } else if (kind == 1) {
      frame.length = draw(9);
    } else if (kind == 2) {
      frame.fd = true;
      frame.fd_flags = draw(16);
      frame.length = FdLengthFromDlc(draw(16));
    } else {
      frame.error = true;
      frame.extended = false;
      frame.length = 8;
    }
    for (std::size_t b = 0; b < frame.payload().size(); ++b) frame.data[b] = draw(256);
    const CandumpFormatted formatted =
        FormatCandumpLine(frame, {}, CandumpDirection::kUnknown, out);
    ASSERT_GT(formatted.size, 0u) << "seed " << kSeed << " case " << i << ": " << formatted.error;
    const Parsed p = Parse({out.data(), formatted.size - 1});
    ASSERT_EQ(p.line.kind, CandumpLineKind::kFrame) << "seed " << kSeed << " case " << i << ": "
                                                    << std::string_view(out.data(), formatted.size);
    EXPECT_EQ(p.frame.time_ns, frame.time_ns);
    EXPECT_EQ(p.frame.id, frame.id);
    EXPECT_EQ(p.frame.extended, frame.extended);
    EXPECT_EQ(p.frame.remote, frame.remote);
    EXPECT_EQ(p.frame.error, frame.error);
    EXPECT_EQ(p.frame.fd, frame.fd);
    EXPECT_EQ(p.frame.fd_flags, frame.fd_flags);
    EXPECT_EQ(p.frame.length, frame.length);
    EXPECT_EQ(Payload(p.frame), Payload(frame));
    EXPECT_EQ(p.frame.interface_name(), frame.interface_name());
  }
}

}  // namespace
}  // namespace flat2d::hal::can
