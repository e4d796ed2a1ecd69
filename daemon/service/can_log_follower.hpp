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
//
// On a vehicle the CAN bus keeps talking while the LiDAR is silent (a cable, a sensor
// restart). With `run_through_silence`, once no packet has counted for kSilence of wall
// time, the log runs on at the pace the packets last kept (the replay's rate), so odometry
// carries the pose through the gap as it would live; the LiDAR's return after the gap is a
// jump, confirmed by its next packet like any pause. A pcap source leaves it off: the end of
// the file is the end of the drive, not a silence.
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
  explicit CanLogFollower(hal::can::CandumpReader log, bool run_through_silence = false);

  // Calls push(const hal::can::CanFrame&) for every frame not after the payload's packet
  // time. Other payloads (position packets) release nothing. `wall_ns` is the monotonic
  // time the payload arrived, which paces the log through a silence.
  template <typename Push>
  void ReleaseUntil(std::span<const std::uint8_t> payload, TimeNs wall_ns, Push&& push) {
    if (!have_frame_) return;
    const TimeNs packet_ns = Plausible(DataPacketTime(payload, next_.time_ns));
    if (packet_ns == 0) return;
    KeepPace(packet_ns, wall_ns);
    ReleaseUpTo(packet_ns, push);
  }

  // Called when the input is idle: after kSilence without a counted packet, and only with
  // run_through_silence, releases the frames up to where the log's clock has run to since.
  template <typename Push>
  void ReleaseThroughSilence(TimeNs wall_ns, Push&& push) {
    if (!run_through_silence_ || !have_frame_ || paced_wall_ns_ == 0) return;
    if (wall_ns - paced_wall_ns_ < kSilence) return;
    const auto elapsed = static_cast<double>(wall_ns - paced_wall_ns_);
    ReleaseUpTo(paced_packet_ns_ + static_cast<TimeNs>(rate_ * elapsed), push);
  }

  bool finished() const { return !have_frame_; }
  // Log seconds per wall second, as the packets last kept it (1 until measured).
  double rate() const { return rate_; }
  static constexpr TimeNs kSilence = 300 * kNsPerMs;  // three revolutions at 10 Hz
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

  template <typename Push>
  void ReleaseUpTo(TimeNs log_ns, Push& push) {
    while (have_frame_ && next_.time_ns <= log_ns) {
      push(next_);
      ++released_;
      have_frame_ = log_.Next(next_);
    }
  }

  // The replay's rate, measured between anchors at least kRateSpan of wall time apart; a
  // jump (a gap in the packets) restarts the measurement rather than entering it.
  static constexpr TimeNs kRateSpan = 2 * kNsPerSecond;
  void KeepPace(TimeNs packet_ns, TimeNs wall_ns);
  bool run_through_silence_ = false;
  double rate_ = 1.0;
  TimeNs paced_packet_ns_ = 0;  // the last counted packet, and when it arrived
  TimeNs paced_wall_ns_ = 0;
  TimeNs anchor_packet_ns_ = 0;
  TimeNs anchor_wall_ns_ = 0;
};

}  // namespace flat2d::daemon
