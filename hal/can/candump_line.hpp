// One line of a candump -l log, parsed and formatted the way can-utils does it.
//
// candump -l (can-utils candump.c and lib.c sprint_canframe) writes one frame per line,
// "(%010lu.%06lu) %*s %s" plus " T"/" R" with -x: the receive time as seconds.microseconds,
// the interface, and the frame as <id>#<data hex>, where the id has 3 hex digits for a
// standard frame and 8 for an extended one or for an error frame (CAN_ERR_FLAG 0x20000000
// printed in the id, linux/can/error.h), <id>#R[dlc] is a remote frame and
// <id>##<flags nibble><data hex> a CAN FD frame (linux/can.h: lengths 0-8, 12, 16, 20,
// 24, 32, 48, 64). ParseCandumpLine: (1) skips blank lines, '#' comments and candump's
// "DROPCOUNT:" notices; (2) reads the time's integer and fraction digits as integers, so
// TimeNs is exact (no float rounding); (3) reads the interface (at most 15 characters,
// IFNAMSIZ); (4) reads id, form and data and checks them against the CAN length rules;
// (5) accepts candump -x's direction marker. Every refusal has a reason and nothing is
// allocated. FormatCandumpLine is the inverse, byte for byte on candump's own output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "hal/can/can_frame.hpp"

namespace flat2d::hal::can {

// Longer lines are malformed; the longest valid one (FD, 64 bytes) is under 200.
inline constexpr std::size_t kMaxCandumpLineBytes = 1024;
// Room FormatCandumpLine needs, including the newline, for any frame and format.
inline constexpr std::size_t kMaxCandumpFormattedBytes = 256;

enum class CandumpLineKind : std::uint8_t {
  kFrame,       // the frame was filled in
  kIgnored,     // blank or a '#' comment
  kDropNotice,  // candump's "DROPCOUNT: dropped N CAN frames ..." line
  kMalformed,
};

// candump -x marks frames sent by this host (MSG_DONTROUTE) with T, received ones with R.
enum class CandumpDirection : std::uint8_t { kUnknown, kReceived, kTransmitted };

enum class CandumpError : std::uint8_t {
  kNone,
  kLineTooLong,
  kNoTimestamp,
  kBadTimestamp,
  kNoInterface,
  kInterfaceTooLong,
  kNoFrame,
  kBadIdLength,
  kBadIdHex,
  kStandardIdTooLarge,
  kExtendedIdTooLarge,
  kErrorFrameForm,
  kBadRemote,
  kBadFdFlags,
  kBadDataHex,
  kOddDataDigits,
  kClassicDataTooLong,
  kFdDataTooLong,
  kInvalidFdLength,
  kTrailingText,
};

// A short English reason, e.g. "CAN FD length is not 0-8, 12, 16, 20, 24, 32, 48 or 64".
std::string_view DescribeCandumpError(CandumpError error);

struct CandumpLine {
  CandumpLineKind kind = CandumpLineKind::kIgnored;
  CandumpError error = CandumpError::kNone;  // why, when kind is kMalformed
  CandumpDirection direction = CandumpDirection::kUnknown;
};

// Parses one line (without its '\n'; a trailing '\r' is tolerated). `frame` is
// overwritten whatever the outcome and is meaningful only for kFrame. The CAN FD flags
// nibble is kept as written (candump >= 2023 includes CANFD_FDF 0x04 in it), and a
// classic frame's raw-DLC suffix "_<dlc>" (len8_dlc) is accepted but not kept.
CandumpLine ParseCandumpLine(std::string_view line, CanFrame& frame);

struct CandumpFormat {
  // Minimum digits of the seconds: candump writes "%010lu"; 0 writes them unpadded.
  int seconds_digits = 10;
  // candump right-aligns interface names to the longest one it listens on ("%*s").
  int interface_width = 0;
  // Written for frames whose interface name is empty.
  std::string_view fallback_interface = "can0";
};

struct CandumpFormatted {
  std::size_t size = 0;     // bytes written to the buffer, newline included; 0 on error
  std::string_view error;   // why the frame cannot be written; empty on success
};

// Formats `frame` as a candump -l line ending in '\n' into `out` (kMaxCandumpFormattedBytes
// suffice). Times are truncated to microseconds as candump's timeval is; times before
// zero, ids beyond their width and lengths CAN does not allow are refused.
CandumpFormatted FormatCandumpLine(const CanFrame& frame, const CandumpFormat& format,
                                   CandumpDirection direction, std::span<char> out);

}  // namespace flat2d::hal::can
