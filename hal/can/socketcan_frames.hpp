// The pure parts of a SocketCAN source: receive filters, frame conversion, error classes.
//
// Kept apart from the socket (socketcan_source.hpp) so that everything above the socket is
// tested on machines without AF_CAN. Following the kernel's SocketCAN documentation
// (Documentation/networking/can.rst) and linux/can.h, linux/can/error.h:
// (1) BuildCanFilters turns configured ids into CAN_RAW_FILTER entries that match
// "received_can_id & mask == can_id & mask", with CAN_EFF_FLAG and CAN_RTR_FLAG in the
// mask so a standard id never matches the extended id of the same number and remote
// frames (no data, useless for odometry) are not delivered; (2) ConvertRawFrame reads a
// struct can_frame (CAN_MTU bytes) or canfd_frame (CANFD_MTU bytes) as read(2) returns it,
// splitting the EFF/RTR/ERR flags out of can_id; (3) ClassifyErrorFrame decodes an error
// frame's class bits (in the id) and controller state (data[1]) for the counters.
#pragma once

#include <linux/can.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "hal/can/can_frame.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

struct CanIdSpec {
  std::uint32_t id = 0;
  bool extended = false;  // 29-bit identifier
};

// One filter per distinct id, in ascending order; at most CAN_RAW_FILTER_MAX (512).
// An id beyond its width is an error naming it. No ids: no filters (receive everything).
Result<std::vector<can_filter>> BuildCanFilters(std::span<const CanIdSpec> ids);

enum class RawFrameKind : std::uint8_t {
  kData,     // a data or remote frame (classic or FD)
  kError,    // an error frame (CAN_ERR_FLAG): out.error is set, out.id holds the class
  kInvalid,  // a size other than CAN_MTU / CANFD_MTU (e.g. CAN XL), or a bad length
};

// Fills `out` (interface name left empty) from `bytes` bytes read into `raw`.
RawFrameKind ConvertRawFrame(const canfd_frame& raw, std::size_t bytes, TimeNs time_ns,
                             CanFrame& out);
RawFrameKind ConvertRawFrame(const can_frame& raw, TimeNs time_ns, CanFrame& out);

// What an error frame reports (linux/can/error.h). Several classes can be set at once.
struct CanErrorFrameInfo {
  bool tx_timeout = false;          // CAN_ERR_TX_TIMEOUT
  bool lost_arbitration = false;    // CAN_ERR_LOSTARB
  bool controller_problem = false;  // CAN_ERR_CRTL, details below
  bool protocol_violation = false;  // CAN_ERR_PROT
  bool transceiver = false;         // CAN_ERR_TRX
  bool no_ack = false;              // CAN_ERR_ACK
  bool bus_off = false;             // CAN_ERR_BUSOFF
  bool bus_error = false;           // CAN_ERR_BUSERROR
  bool restarted = false;           // CAN_ERR_RESTARTED
  bool rx_overflow = false;         // controller: CAN_ERR_CRTL_RX_OVERFLOW
  bool tx_overflow = false;         // controller: CAN_ERR_CRTL_TX_OVERFLOW
  bool error_warning = false;       // controller: RX or TX warning level reached
  bool error_passive = false;       // controller: RX or TX error passive
  bool back_to_active = false;      // controller: CAN_ERR_CRTL_ACTIVE
};

CanErrorFrameInfo ClassifyErrorFrame(const CanFrame& frame);

// Error frames seen, by class; a frame counts in every class it reports.
struct CanErrorCounts {
  std::uint64_t frames = 0;
  std::uint64_t bus_off = 0;
  std::uint64_t error_passive = 0;
  std::uint64_t error_warning = 0;
  std::uint64_t controller_overflow = 0;  // RX or TX buffer overflow in the controller
  std::uint64_t protocol_violation = 0;
  std::uint64_t no_ack = 0;
  std::uint64_t lost_arbitration = 0;
  std::uint64_t bus_error = 0;
  std::uint64_t other = 0;  // TX timeout, transceiver, restarted, back to active
};

void CountErrorFrame(const CanErrorFrameInfo& info, CanErrorCounts& counts);

}  // namespace flat2d::hal::can
