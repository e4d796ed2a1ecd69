// FormatCandumpLine (candump_line.hpp), apart from the parser to keep each file short.
#include <array>

#include "hal/can/candump_line.hpp"

namespace flat2d::hal::can {
namespace {

constexpr std::string_view kHexDigits = "0123456789ABCDEF";
constexpr int kMaxDecimalDigits = 20;  // of a uint64
constexpr int kMaxInterfaceWidth = 16;

// Appends to a caller's buffer; remembers overflow instead of writing past the end.
class LineOutput {
 public:
  explicit LineOutput(std::span<char> out) : out_(out) {}

  void Put(char c) {
    if (size_ < out_.size()) {
      out_[size_++] = c;
    } else {
      overflow_ = true;
    }
  }
  void Put(std::string_view text) {
    for (const char c : text) Put(c);
  }
  void PutRepeated(char c, int count) {
    for (int i = 0; i < count; ++i) Put(c);
  }
  void PutHex(std::uint32_t value, int digits) {
    for (int shift = (digits - 1) * 4; shift >= 0; shift -= 4) {
      Put(kHexDigits[(value >> shift) & 0xF]);
    }
  }
  void PutDecimal(std::uint64_t value, int min_digits) {
    std::array<char, kMaxDecimalDigits> reversed{};
    int count = 0;
    do {
      reversed[static_cast<std::size_t>(count++)] = static_cast<char>('0' + value % 10);
      value /= 10;
    } while (value != 0);
    PutRepeated('0', min_digits - count);
    while (count > 0) Put(reversed[static_cast<std::size_t>(--count)]);
  }

  std::size_t size() const { return overflow_ ? 0 : size_; }

 private:
  std::span<char> out_;
  std::size_t size_ = 0;
  bool overflow_ = false;
};

// The refusals mirror the parser's, so that whatever is written can be read back.
std::string_view CheckWritable(const CanFrame& frame, const CandumpFormat& format) {
  if (format.seconds_digits < 0 || format.seconds_digits > kMaxDecimalDigits) {
    return "seconds_digits is not 0..20";
  }
  if (format.interface_width < 0 || format.interface_width > kMaxInterfaceWidth) {
    return "interface_width is not 0..16";
  }
  if (frame.time_ns < 0) return "times before zero cannot be written";
  if (frame.error) {
    if (frame.id > kMaxExtendedId) return "error class above 0x1FFFFFFF";
    if (frame.remote || frame.fd) return "error frames are classic data frames";
  } else if (frame.extended ? frame.id > kMaxExtendedId : frame.id > kMaxStandardId) {
    return frame.extended ? "extended id above 0x1FFFFFFF" : "standard id above 0x7FF";
  }
  if (frame.fd) {
    if (frame.remote) return "CAN FD frames have no remote form";
    if (!IsValidFdLength(frame.length)) return "CAN FD length is not a valid DLC step";
  } else if (frame.length > kMaxClassicDataBytes) {
    return "classic CAN frame longer than 8 bytes";
  }
  return {};
}

// lib.c sprint_canframe without separators, as candump -l calls it.
void PutFrame(const CanFrame& frame, LineOutput& out) {
  if (frame.error) {
    out.PutHex(frame.id | kCanErrorFlag, 8);
  } else {
    out.PutHex(frame.id, frame.extended ? 8 : 3);
  }
  out.Put('#');
  if (frame.remote) {
    out.Put('R');
    if (frame.length > 0) out.Put(kHexDigits[frame.length]);
    return;
  }
  if (frame.fd) {
    out.Put('#');
    out.Put(kHexDigits[frame.fd_flags & 0xF]);
  }
  for (const std::uint8_t byte : frame.payload()) out.PutHex(byte, 2);
}

}  // namespace

CandumpFormatted FormatCandumpLine(const CanFrame& frame, const CandumpFormat& format,
                                   CandumpDirection direction, std::span<char> out) {
  if (const std::string_view error = CheckWritable(frame, format); !error.empty()) {
    return {0, error};
  }
  LineOutput line(out);
  // candump prints a struct timeval: whole microseconds, the rest truncated.
  line.Put('(');
  line.PutDecimal(static_cast<std::uint64_t>(frame.time_ns / kNsPerSecond), format.seconds_digits);
  line.Put('.');
  line.PutDecimal(static_cast<std::uint64_t>(frame.time_ns % kNsPerSecond / kNsPerUs), 6);
  line.Put(") ");
  std::string_view name = frame.interface_name();
  if (name.empty()) name = format.fallback_interface;
  line.PutRepeated(' ', format.interface_width - static_cast<int>(name.size()));
  line.Put(name);
  line.Put(' ');
  PutFrame(frame, line);
  if (direction == CandumpDirection::kReceived) line.Put(" R");
  if (direction == CandumpDirection::kTransmitted) line.Put(" T");
  line.Put('\n');
  if (line.size() == 0) return {0, "output buffer too small for the line"};
  return {line.size(), {}};
}

}  // namespace flat2d::hal::can
