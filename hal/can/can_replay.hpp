// Replaying a CAN log with its original timing, scaled: a CanFrameSource over another one.
//
// Offline runs of the daemon and the tools consume a candump log as if it came from the
// bus. Steps, per frame pulled from the wrapped source: (1) the first frame fixes the
// schedule's origin, log time t0 at replay-clock time c0; (2) each later frame is due at
// c0 + (t - t0) / speed, computed from the origin and not from the previous frame, so a
// late consumer does not push back the frames after it; (3) the source sleeps until then
// on the injectable hal::net::ReplayClock (a fake one in tests); (4) a frame whose log
// time goes backwards (merged or concatenated logs) is released at once and counted,
// never slept for; a step back of more than rebase_after_backward_ns (a log restarted,
// a clock reset) also moves the origin, so the frames after it keep their spacing instead
// of rushing out until the log time catches up. speed <= 0 releases every frame as soon
// as the consumer asks.
#pragma once

#include <cstdint>

#include "hal/can/can_frame.hpp"
#include "hal/common/time.hpp"
#include "hal/net/replay.hpp"

namespace flat2d::hal::can {

struct CanReplayOptions {
  double speed = 1.0;  // 2 replays twice as fast; <= 0 as fast as the consumer takes frames
  TimeNs rebase_after_backward_ns = kNsPerSecond;
};

struct CanReplayStats {
  std::uint64_t frames = 0;          // frames released
  std::uint64_t sleeps = 0;          // frames that had to wait for their time
  std::uint64_t non_monotonic = 0;   // frames whose log time went backwards
  std::uint64_t rebased = 0;         // of them, steps back large enough to move the origin
  TimeNs largest_backward_step_ns = 0;
};

class CanReplaySource final : public CanFrameSource {
 public:
  // Both references must outlive this source.
  CanReplaySource(CanFrameSource& source, net::ReplayClock& clock, CanReplayOptions options = {});

  bool Next(CanFrame& frame) override;
  const CanReplayStats& stats() const { return stats_; }

 private:
  // The frame's offset on the log's time line from the (possibly rebased) origin.
  TimeNs LogOffset(TimeNs log_time_ns);
  void WaitFor(TimeNs log_offset_ns);

  CanFrameSource& source_;
  net::ReplayClock& clock_;
  CanReplayOptions options_;
  bool started_ = false;
  TimeNs origin_log_ns_ = 0;    // t0
  TimeNs origin_clock_ns_ = 0;  // c0
  TimeNs latest_log_ns_ = 0;    // the largest log time released so far
  CanReplayStats stats_;
};

}  // namespace flat2d::hal::can
