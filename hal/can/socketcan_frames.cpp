#include "hal/can/socketcan_frames.hpp"

#include <linux/can/error.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace flat2d::hal::can {
namespace {

// Match the id, the frame format and "not remote" (SocketCAN docs, RAW filter examples).
constexpr canid_t kStandardMask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
constexpr canid_t kExtendedMask = CAN_EFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;

std::string HexId(std::uint32_t id) {
  char text[16] = {};
  std::snprintf(text, sizeof(text), "0x%X", static_cast<unsigned>(id));
  return text;
}

bool FilterLess(const can_filter& a, const can_filter& b) {
  return a.can_id != b.can_id ? a.can_id < b.can_id : a.can_mask < b.can_mask;
}

bool FilterEqual(const can_filter& a, const can_filter& b) {
  return a.can_id == b.can_id && a.can_mask == b.can_mask;
}

}  // namespace

Result<std::vector<can_filter>> BuildCanFilters(std::span<const CanIdSpec> ids) {
  std::vector<can_filter> filters;
  filters.reserve(ids.size());
  for (const CanIdSpec& spec : ids) {
    if (!spec.extended && spec.id > kMaxStandardId) {
      return MakeError("CAN id " + HexId(spec.id) + " is above 0x7FF, the largest standard id; "
                       "mark it extended if it is a 29-bit id");
    }
    if (spec.extended && spec.id > kMaxExtendedId) {
      return MakeError("extended CAN id " + HexId(spec.id) + " is above 0x1FFFFFFF");
    }
    filters.push_back(spec.extended ? can_filter{spec.id | CAN_EFF_FLAG, kExtendedMask}
                                    : can_filter{spec.id, kStandardMask});
  }
  std::sort(filters.begin(), filters.end(), FilterLess);
  filters.erase(std::unique(filters.begin(), filters.end(), FilterEqual), filters.end());
  if (filters.size() > CAN_RAW_FILTER_MAX) {
    return MakeError(std::to_string(filters.size()) + " CAN ids configured; the kernel takes "
                     "at most " + std::to_string(CAN_RAW_FILTER_MAX) + " receive filters");
  }
  return filters;
}

RawFrameKind ConvertRawFrame(const canfd_frame& raw, std::size_t bytes, TimeNs time_ns,
                             CanFrame& out) {
  if (bytes != CAN_MTU && bytes != CANFD_MTU) return RawFrameKind::kInvalid;
  out = CanFrame{};
  out.time_ns = time_ns;
  const bool fd = bytes == CANFD_MTU;
  std::size_t length = raw.len;
  if ((raw.can_id & CAN_ERR_FLAG) != 0) {
    out.error = true;
    out.id = raw.can_id & CAN_ERR_MASK;
    length = std::min<std::size_t>(length, CAN_ERR_DLC);
  } else {
    out.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    out.id = raw.can_id & (out.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    out.fd = fd;
    // The FD flags nibble as the kernel gives it (CANFD_FDF included since Linux 6.2).
    if (fd) out.fd_flags = raw.flags & 0x0F;
    out.remote = !fd && (raw.can_id & CAN_RTR_FLAG) != 0;
    if (fd ? !IsValidFdLength(length) : length > CAN_MAX_DLEN) return RawFrameKind::kInvalid;
  }
  out.length = static_cast<std::uint8_t>(length);
  if (!out.remote) std::memcpy(out.data.data(), raw.data, length);
  return out.error ? RawFrameKind::kError : RawFrameKind::kData;
}

RawFrameKind ConvertRawFrame(const can_frame& raw, TimeNs time_ns, CanFrame& out) {
  // struct can_frame and canfd_frame share their layout up to data[8] (linux/can.h).
  canfd_frame wide{};
  std::memcpy(&wide, &raw, sizeof(raw));
  return ConvertRawFrame(wide, CAN_MTU, time_ns, out);
}

CanErrorFrameInfo ClassifyErrorFrame(const CanFrame& frame) {
  CanErrorFrameInfo info;
  const std::uint32_t classes = frame.id;
  info.tx_timeout = (classes & CAN_ERR_TX_TIMEOUT) != 0;
  info.lost_arbitration = (classes & CAN_ERR_LOSTARB) != 0;
  info.controller_problem = (classes & CAN_ERR_CRTL) != 0;
  info.protocol_violation = (classes & CAN_ERR_PROT) != 0;
  info.transceiver = (classes & CAN_ERR_TRX) != 0;
  info.no_ack = (classes & CAN_ERR_ACK) != 0;
  info.bus_off = (classes & CAN_ERR_BUSOFF) != 0;
  info.bus_error = (classes & CAN_ERR_BUSERROR) != 0;
  info.restarted = (classes & CAN_ERR_RESTARTED) != 0;
  // data[1] is defined only when the controller class is set.
  const std::uint8_t controller = info.controller_problem ? frame.data[1] : 0;
  info.rx_overflow = (controller & CAN_ERR_CRTL_RX_OVERFLOW) != 0;
  info.tx_overflow = (controller & CAN_ERR_CRTL_TX_OVERFLOW) != 0;
  info.error_warning = (controller & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0;
  info.error_passive = (controller & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0;
  info.back_to_active = (controller & CAN_ERR_CRTL_ACTIVE) != 0;
  return info;
}

void CountErrorFrame(const CanErrorFrameInfo& info, CanErrorCounts& counts) {
  ++counts.frames;
  counts.bus_off += info.bus_off ? 1 : 0;
  counts.error_passive += info.error_passive ? 1 : 0;
  counts.error_warning += info.error_warning ? 1 : 0;
  counts.controller_overflow += (info.rx_overflow || info.tx_overflow) ? 1 : 0;
  counts.protocol_violation += info.protocol_violation ? 1 : 0;
  counts.no_ack += info.no_ack ? 1 : 0;
  counts.lost_arbitration += info.lost_arbitration ? 1 : 0;
  counts.bus_error += info.bus_error ? 1 : 0;
  const bool other = info.tx_timeout || info.transceiver || info.restarted || info.back_to_active;
  counts.other += other ? 1 : 0;
}

}  // namespace flat2d::hal::can
