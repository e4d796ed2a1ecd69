#include "daemon/service/can_log_follower.hpp"

#include <utility>

#include "hal/velodyne/packet_layout.hpp"
#include "hal/velodyne/sensor_clock.hpp"

namespace flat2d::daemon {

TimeNs DataPacketTime(std::span<const std::uint8_t> payload, TimeNs reference_ns) {
  namespace vlp = hal::velodyne;
  if (payload.size() != vlp::kDataPacketSize) return 0;
  const std::uint8_t* stamp = payload.data() + vlp::kTimestampOffset;
  const std::uint32_t us_past_hour = static_cast<std::uint32_t>(stamp[0]) | (static_cast<std::uint32_t>(stamp[1]) << 8) |
                                     (static_cast<std::uint32_t>(stamp[2]) << 16) |
                                     (static_cast<std::uint32_t>(stamp[3]) << 24);
  return vlp::ResolveHourRelative(us_past_hour, reference_ns);
}

CanLogFollower::CanLogFollower(hal::can::CandumpReader log) : log_(std::move(log)) { have_frame_ = log_.Next(next_); }

}  // namespace flat2d::daemon
