#include "daemon/service/can_log_follower.hpp"

#include <algorithm>
#include <utility>

#include "hal/velodyne/packet_layout.hpp"
#include "hal/velodyne/sensor_clock.hpp"

namespace flat2d::daemon {

TimeNs DataPacketTime(std::span<const std::uint8_t> payload, TimeNs reference_ns) {
  namespace vlp = hal::velodyne;
  if (payload.size() != vlp::kDataPacketSize) return 0;
  for (std::size_t block = 0; block < vlp::kBlocksPerPacket; ++block) {
    const std::uint8_t* flag = payload.data() + block * vlp::kBlockSize;
    if ((flag[0] | (flag[1] << 8)) != vlp::kBlockFlag) return 0;
  }
  const std::uint8_t* stamp = payload.data() + vlp::kTimestampOffset;
  const std::uint32_t us_past_hour = static_cast<std::uint32_t>(stamp[0]) | (static_cast<std::uint32_t>(stamp[1]) << 8) |
                                     (static_cast<std::uint32_t>(stamp[2]) << 16) |
                                     (static_cast<std::uint32_t>(stamp[3]) << 24);
  return vlp::ResolveHourRelative(us_past_hour, reference_ns);
}

TimeNs CanLogFollower::Plausible(TimeNs packet_ns) {
  if (packet_ns == 0) return 0;
  const auto near = [](TimeNs a, TimeNs b) { return a - b < kMaxJump && b - a < kMaxJump; };
  if (last_packet_ns_ == 0 || near(packet_ns, last_packet_ns_) || (candidate_ns_ != 0 && near(packet_ns, candidate_ns_))) {
    last_packet_ns_ = packet_ns;
    candidate_ns_ = 0;
    return packet_ns;
  }
  candidate_ns_ = packet_ns;
  ++implausible_;
  return 0;
}

void CanLogFollower::KeepPace(TimeNs packet_ns, TimeNs wall_ns) {
  const bool continuous = paced_wall_ns_ != 0 && packet_ns - paced_packet_ns_ < kMaxJump &&
                          wall_ns - paced_wall_ns_ < kSilence;
  if (!continuous) {
    anchor_packet_ns_ = packet_ns;
    anchor_wall_ns_ = wall_ns;
  } else if (wall_ns - anchor_wall_ns_ >= kRateSpan) {
    // Bounded: a stalled reader (the packets queued, then drained at once) must not make the
    // log run away through the next silence.
    rate_ = std::clamp(static_cast<double>(packet_ns - anchor_packet_ns_) / static_cast<double>(wall_ns - anchor_wall_ns_),
                       0.1, 20.0);
    anchor_packet_ns_ = packet_ns;
    anchor_wall_ns_ = wall_ns;
  }
  paced_packet_ns_ = packet_ns;
  paced_wall_ns_ = wall_ns;
}

CanLogFollower::CanLogFollower(hal::can::CandumpReader log, bool run_through_silence)
    : log_(std::move(log)), run_through_silence_(run_through_silence) {
  have_frame_ = log_.Next(next_);
}

}  // namespace flat2d::daemon
