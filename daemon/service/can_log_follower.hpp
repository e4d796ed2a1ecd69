// A candump log replayed on the LiDAR's clock: before each Velodyne data packet goes to the
// pipeline, the log's frames up to the packet's time go first.
//
// A recorded CAN log has the recording's timestamps; the LiDAR's packets carry the sensor's
// own time (microseconds past the hour, VLP-16 manual 9.3.1.6), which SensorClock resolves
// against GPS or the host. Pacing the log by the packets, not by the wall clock, keeps the
// two in step however the LiDAR is replayed (a pcap at any rate, or UDP from another
// process), which is how a recorded drive is run through the live daemon. A packet's time
// counts only if its block flags are intact and it follows the previous packet's within a
// second (or the next packet confirms the jump), so junk on the port cannot run the log ahead.
#pragma once

#include <cstdint>
#include <span>

#include "hal/can/candump_log.hpp"
#include "hal/common/time.hpp"

namespace flat2d::daemon {

// The time of a 1206-byte Velodyne data packet, resolved into the hour nearest `reference_ns`;
// 0 for any other payload, and for one whose twelve block flags are not 0xFFEE (damaged).
TimeNs DataPacketTime(std::span<const std::uint8_t> payload, TimeNs reference_ns);

class CanLogFollower {
 public:
  explicit CanLogFollower(hal::can::CandumpReader log);

  // Calls push(const hal::can::CanFrame&) for every frame not after the payload's packet
  // time. Other payloads (position packets) release nothing.
  template <typename Push>
  void ReleaseUntil(std::span<const std::uint8_t> payload, Push&& push) {
    if (!have_frame_) return;
    const TimeNs packet_ns = Plausible(DataPacketTime(payload, next_.time_ns));
    if (packet_ns == 0) return;
    while (have_frame_ && next_.time_ns <= packet_ns) {
      push(next_);
      ++released_;
      have_frame_ = log_.Next(next_);
    }
  }

  bool finished() const { return !have_frame_; }
  // Packets whose time jumped from the previous packet's and was not confirmed by the next.
  std::uint64_t implausible() const { return implausible_; }
  std::uint64_t released() const { return released_; }
  const hal::can::CandumpReaderStats& stats() const { return log_.stats(); }

 private:
  hal::can::CandumpReader log_;
  hal::can::CanFrame next_;
  bool have_frame_ = false;
  std::uint64_t released_ = 0;
  std::uint64_t implausible_ = 0;

  // A packet more than kMaxJump from the previous one is believed only when the next packet
  // agrees with it: one damaged timestamp must not fast-forward the log.
  static constexpr TimeNs kMaxJump = kNsPerSecond;
  TimeNs Plausible(TimeNs packet_ns);
  TimeNs last_packet_ns_ = 0;
  TimeNs candidate_ns_ = 0;
};

}  // namespace flat2d::daemon
