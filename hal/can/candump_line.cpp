#include "hal/can/candump_line.hpp"

#include <array>
#include <limits>

namespace flat2d::hal::can {
namespace {

constexpr std::uint32_t kFlagsAboveErrorFlag = 0xC0000000;  // CAN_EFF_FLAG | CAN_RTR_FLAG
// The largest whole second whose nanoseconds, plus a fraction, still fit in TimeNs.
constexpr std::uint64_t kMaxSeconds = std::numeric_limits<TimeNs>::max() / kNsPerSecond - 1;
constexpr int kMaxFractionDigits = 9;  // nanoseconds
constexpr std::string_view kDropNoticePrefix = "DROPCOUNT:";

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view Trim(std::string_view text) {
  while (!text.empty() && IsBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && IsBlank(text.back())) text.remove_suffix(1);
  return text;
}

// Splits off the next blank-delimited token of `rest`.
std::string_view NextToken(std::string_view& rest) {
  while (!rest.empty() && IsBlank(rest.front())) rest.remove_prefix(1);
  std::size_t end = 0;
  while (end < rest.size() && !IsBlank(rest[end])) ++end;
  const std::string_view token = rest.substr(0, end);
  rest.remove_prefix(end);
  return token;
}

// "(seconds.fraction)", both parts read as integers so the nanoseconds are exact.
CandumpError ParseTimestamp(std::string_view token, TimeNs& time_ns) {
  if (token.empty() || token.front() != '(') return CandumpError::kNoTimestamp;
  if (token.size() < 2 || token.back() != ')') return CandumpError::kBadTimestamp;
  const std::string_view body = token.substr(1, token.size() - 2);
  const std::size_t dot = body.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == body.size() ||
      body.size() - dot - 1 > kMaxFractionDigits) {
    return CandumpError::kBadTimestamp;
  }
  std::uint64_t seconds = 0;
  for (const char c : body.substr(0, dot)) {
    if (c < '0' || c > '9') return CandumpError::kBadTimestamp;
    seconds = seconds * 10 + static_cast<std::uint64_t>(c - '0');
    if (seconds > kMaxSeconds) return CandumpError::kBadTimestamp;
  }
  TimeNs fraction_ns = 0;
  int digits = 0;
  for (const char c : body.substr(dot + 1)) {
    if (c < '0' || c > '9') return CandumpError::kBadTimestamp;
    fraction_ns = fraction_ns * 10 + (c - '0');
    ++digits;
  }
  for (; digits < kMaxFractionDigits; ++digits) fraction_ns *= 10;
  time_ns = static_cast<TimeNs>(seconds) * kNsPerSecond + fraction_ns;
  return CandumpError::kNone;
}

// 3 digits: standard id; 8 digits: extended id, or an error class if CAN_ERR_FLAG is set
// (lib.c parse_canframe sets CAN_EFF_FLAG only when the error flag is absent).
CandumpError ParseId(std::string_view digits, CanFrame& frame) {
  if (digits.size() != 3 && digits.size() != 8) return CandumpError::kBadIdLength;
  std::uint32_t value = 0;
  for (const char c : digits) {
    const int nibble = HexValue(c);
    if (nibble < 0) return CandumpError::kBadIdHex;
    value = (value << 4) | static_cast<std::uint32_t>(nibble);
  }
  if (digits.size() == 3) {
    if (value > kMaxStandardId) return CandumpError::kStandardIdTooLarge;
  } else if ((value & kCanErrorFlag) != 0) {
    if ((value & kFlagsAboveErrorFlag) != 0) return CandumpError::kErrorFrameForm;
    frame.error = true;
    value &= kMaxExtendedId;
  } else if (value > kMaxExtendedId) {
    return CandumpError::kExtendedIdTooLarge;
  } else {
    frame.extended = true;
  }
  frame.id = value;
  return CandumpError::kNone;
}

// "_<9..F>": the raw DLC of an 8-byte classic frame (len8_dlc), newer can-utils only.
bool IsRawDlcSuffix(std::string_view text) {
  return text.size() == 2 && text[0] == '_' && HexValue(text[1]) > 8;
}

// "R", or "R<dlc 0-8>" optionally followed by a raw DLC suffix.
CandumpError ParseRemote(std::string_view text, CanFrame& frame) {
  frame.remote = true;
  if (text.empty()) return CandumpError::kNone;
  const int dlc = HexValue(text.front());
  if (dlc < 0 || dlc > static_cast<int>(kMaxClassicDataBytes)) return CandumpError::kBadRemote;
  frame.length = static_cast<std::uint8_t>(dlc);
  text.remove_prefix(1);
  if (text.empty() || (dlc == 8 && IsRawDlcSuffix(text))) return CandumpError::kNone;
  return CandumpError::kBadRemote;
}

// Hex byte pairs into frame.data, skipping lib.c's optional '.' separators; stops at
// the first character that starts no byte and leaves it in `text`.
CandumpError ParseData(std::string_view& text, std::size_t max_bytes, CandumpError too_long,
                       CanFrame& frame) {
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
      continue;
    }
    const int high = HexValue(text[i]);
    if (high < 0) break;
    if (count == max_bytes) return too_long;
    if (i + 1 >= text.size()) return CandumpError::kOddDataDigits;
    const int low = HexValue(text[i + 1]);
    if (low < 0) {
      const bool separator = text[i + 1] == '.' || text[i + 1] == '_';
      return separator ? CandumpError::kOddDataDigits : CandumpError::kBadDataHex;
    }
    frame.data[count++] = static_cast<std::uint8_t>((high << 4) | low);
    i += 2;
  }
  frame.length = static_cast<std::uint8_t>(count);
  text.remove_prefix(i);
  return CandumpError::kNone;
}

CandumpError ParseFdData(std::string_view text, CanFrame& frame) {
  frame.fd = true;
  const int flags = text.empty() ? -1 : HexValue(text.front());
  if (flags < 0) return CandumpError::kBadFdFlags;
  frame.fd_flags = static_cast<std::uint8_t>(flags);
  text.remove_prefix(1);
  const CandumpError error =
      ParseData(text, kMaxFdDataBytes, CandumpError::kFdDataTooLong, frame);
  if (error != CandumpError::kNone) return error;
  if (!text.empty()) return CandumpError::kBadDataHex;
  if (!IsValidFdLength(frame.length)) return CandumpError::kInvalidFdLength;
  return CandumpError::kNone;
}

// "<id>#<data>", "<id>#R[dlc]" or "<id>##<flags><data>".
CandumpError ParseFrameText(std::string_view text, CanFrame& frame) {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) return CandumpError::kBadIdLength;
  if (const CandumpError error = ParseId(text.substr(0, hash), frame);
      error != CandumpError::kNone) {
    return error;
  }
  std::string_view rest = text.substr(hash + 1);
  const bool remote = !rest.empty() && (rest.front() == 'R' || rest.front() == 'r');
  const bool fd = !rest.empty() && rest.front() == '#';
  // Error frames are classic 8-byte frames (CAN_ERR_DLC); there are no RTR or FD ones.
  if (frame.error && (remote || fd)) return CandumpError::kErrorFrameForm;
  if (remote) return ParseRemote(rest.substr(1), frame);
  if (fd) return ParseFdData(rest.substr(1), frame);
  const CandumpError error =
      ParseData(rest, kMaxClassicDataBytes, CandumpError::kClassicDataTooLong, frame);
  if (error != CandumpError::kNone) return error;
  if (rest.empty() || (frame.length == kMaxClassicDataBytes && IsRawDlcSuffix(rest))) {
    return CandumpError::kNone;
  }
  return CandumpError::kBadDataHex;
}

CandumpLine Malformed(CandumpError error) {
  return {CandumpLineKind::kMalformed, error, CandumpDirection::kUnknown};
}

}  // namespace

std::string_view DescribeCandumpError(CandumpError error) {
  switch (error) {
    case CandumpError::kNone: return "no error";
    case CandumpError::kLineTooLong: return "line longer than 1024 bytes";
    case CandumpError::kNoTimestamp: return "no '(seconds.fraction)' timestamp";
    case CandumpError::kBadTimestamp:
      return "timestamp is not (seconds.fraction) with 1-9 fraction digits";
    case CandumpError::kNoInterface: return "no interface name";
    case CandumpError::kInterfaceTooLong: return "interface name longer than 15 characters";
    case CandumpError::kNoFrame: return "no frame after the interface name";
    case CandumpError::kBadIdLength: return "id is not 3 or 8 hex digits followed by '#'";
    case CandumpError::kBadIdHex: return "id has a character that is not a hex digit";
    case CandumpError::kStandardIdTooLarge: return "3-digit (standard) id above 0x7FF";
    case CandumpError::kExtendedIdTooLarge: return "8-digit (extended) id above 0x1FFFFFFF";
    case CandumpError::kErrorFrameForm:
      return "error frame (CAN_ERR_FLAG id) that is not a classic data frame";
    case CandumpError::kBadRemote: return "remote frame is not 'R' or 'R<dlc 0-8>'";
    case CandumpError::kBadFdFlags: return "CAN FD '##' without a hex flags digit";
    case CandumpError::kBadDataHex: return "data has a character that is not a hex digit";
    case CandumpError::kOddDataDigits: return "data has an odd number of hex digits";
    case CandumpError::kClassicDataTooLong: return "classic CAN data longer than 8 bytes";
    case CandumpError::kFdDataTooLong: return "CAN FD data longer than 64 bytes";
    case CandumpError::kInvalidFdLength:
      return "CAN FD length is not 0-8, 12, 16, 20, 24, 32, 48 or 64";
    case CandumpError::kTrailingText: return "text after the frame that is not a T/R direction";
  }
  return "unknown error";
}

CandumpLine ParseCandumpLine(std::string_view line, CanFrame& frame) {
  frame = CanFrame{};
  std::string_view rest = Trim(line);
  if (rest.empty() || rest.front() == '#') return {};
  if (rest.starts_with(kDropNoticePrefix)) return {CandumpLineKind::kDropNotice};
  if (const CandumpError error = ParseTimestamp(NextToken(rest), frame.time_ns);
      error != CandumpError::kNone) {
    return Malformed(error);
  }
  const std::string_view interface_name = NextToken(rest);
  if (interface_name.empty()) return Malformed(CandumpError::kNoInterface);
  if (interface_name.size() >= kMaxInterfaceName) return Malformed(CandumpError::kInterfaceTooLong);
  frame.set_interface_name(interface_name);
  const std::string_view frame_text = NextToken(rest);
  if (frame_text.empty()) return Malformed(CandumpError::kNoFrame);
  if (const CandumpError error = ParseFrameText(frame_text, frame); error != CandumpError::kNone) {
    return Malformed(error);
  }
  CandumpLine parsed{CandumpLineKind::kFrame, CandumpError::kNone, CandumpDirection::kUnknown};
  const std::string_view marker = NextToken(rest);
  if (marker == "R") parsed.direction = CandumpDirection::kReceived;
  if (marker == "T") parsed.direction = CandumpDirection::kTransmitted;
  if ((!marker.empty() && parsed.direction == CandumpDirection::kUnknown) || !rest.empty()) {
    return Malformed(CandumpError::kTrailingText);
  }
  return parsed;
}

}  // namespace flat2d::hal::can
