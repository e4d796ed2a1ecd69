// One CAN or CAN FD frame as received from a bus or read from a log.
//
// Mirrors Linux SocketCAN's struct canfd_frame (can.h): an 11- or 29-bit identifier with
// the EFF/RTR/ERR flags split out, up to 8 data bytes (64 for CAN FD), and the receive
// time. CAN FD lengths are restricted to the DLC steps 0-8, 12, 16, 20, 24, 32, 48, 64.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "hal/common/time.hpp"

namespace flat2d::hal::can {

inline constexpr std::size_t kMaxClassicDataBytes = 8;
inline constexpr std::size_t kMaxFdDataBytes = 64;
inline constexpr std::uint32_t kMaxStandardId = 0x7FF;
inline constexpr std::uint32_t kMaxExtendedId = 0x1FFFFFFF;
inline constexpr std::size_t kMaxInterfaceName = 16;  // IFNAMSIZ, including the NUL
inline constexpr std::uint32_t kCanErrorFlag = 0x20000000;  // CAN_ERR_FLAG (linux/can.h)

struct CanFrame {
  TimeNs time_ns = 0;          // receive time: kernel stamp (Unix epoch) or the log's clock
  std::uint32_t id = 0;        // 11-bit (standard) or 29-bit (extended) identifier
  bool extended = false;       // 29-bit identifier (CAN_EFF_FLAG)
  bool remote = false;         // remote transmission request (CAN_RTR_FLAG); no data
  bool error = false;          // error frame (CAN_ERR_FLAG); id holds the error class
  bool fd = false;             // CAN FD frame
  std::uint8_t fd_flags = 0;   // CANFD_BRS (0x01) / CANFD_ESI (0x02)
  std::uint8_t length = 0;     // data bytes in use (remote frames: the requested DLC)
  std::array<std::uint8_t, kMaxFdDataBytes> data{};
  std::array<char, kMaxInterfaceName> interface{};  // NUL-terminated, e.g. "can0"; may be empty

  std::span<const std::uint8_t> payload() const { return {data.data(), remote ? 0u : length}; }
  std::string_view interface_name() const;
  void set_interface_name(std::string_view name);  // truncated to 15 characters
};

// CAN FD data length codes: DLC 0-15 <-> lengths 0-8, 12, 16, 20, 24, 32, 48, 64.
std::uint8_t FdLengthFromDlc(std::uint8_t dlc);
// The smallest valid CAN FD length >= `length` (e.g. 9 -> 12); lengths > 64 give 64.
std::uint8_t FdRoundUpLength(std::size_t length);
bool IsValidFdLength(std::size_t length);

// The frame's identifier as candump prints it: 3 hex digits, or 8 for extended ids.
std::array<char, 9> FormatCanId(const CanFrame& frame);

// Abstract source of frames (a live bus, a log file, a timed replay).
class CanFrameSource {
 public:
  virtual ~CanFrameSource() = default;
  // Fills `frame` with the next frame and returns true; false when none is available
  // (end of a log, or for a live bus nothing within the source's wait). Filling a
  // caller-owned frame keeps hot loops free of copies and allocation.
  virtual bool Next(CanFrame& frame) = 0;

 protected:
  CanFrameSource() = default;
  CanFrameSource(const CanFrameSource&) = default;
  CanFrameSource& operator=(const CanFrameSource&) = default;
};

}  // namespace flat2d::hal::can
