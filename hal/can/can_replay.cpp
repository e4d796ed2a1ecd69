#include "hal/can/can_replay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flat2d::hal::can {
namespace {

// Far beyond any log (~30 years) yet safe to add to a monotonic clock reading.
constexpr double kMaxScheduleOffsetNs = 1e18;

// a - b, saturated: frame times from arbitrary sources must not overflow the schedule.
TimeNs SaturatingDifference(TimeNs a, TimeNs b) {
  TimeNs difference = 0;
  if (!__builtin_sub_overflow(a, b, &difference)) return difference;
  return a > b ? std::numeric_limits<TimeNs>::max() : std::numeric_limits<TimeNs>::min();
}

}  // namespace

CanReplaySource::CanReplaySource(CanFrameSource& source, net::ReplayClock& clock,
                                 CanReplayOptions options)
    : source_(source), clock_(clock), options_(options) {}

bool CanReplaySource::Next(CanFrame& frame) {
  if (!source_.Next(frame)) return false;
  const TimeNs log_offset_ns = LogOffset(frame.time_ns);
  if (options_.speed > 0) WaitFor(log_offset_ns);
  ++stats_.frames;
  return true;
}

TimeNs CanReplaySource::LogOffset(TimeNs log_time_ns) {
  if (!started_) {
    started_ = true;
    origin_log_ns_ = latest_log_ns_ = log_time_ns;
    if (options_.speed > 0) origin_clock_ns_ = clock_.Now();
    return 0;
  }
  if (log_time_ns < latest_log_ns_) {
    // Released at once: its due time is before the latest frame's, which has passed.
    const TimeNs step_ns = SaturatingDifference(latest_log_ns_, log_time_ns);
    ++stats_.non_monotonic;
    stats_.largest_backward_step_ns = std::max(stats_.largest_backward_step_ns, step_ns);
    if (step_ns <= options_.rebase_after_backward_ns) {
      return SaturatingDifference(log_time_ns, origin_log_ns_);
    }
    // A restarted log: the frames after this one keep their spacing from now on.
    ++stats_.rebased;
    origin_log_ns_ = log_time_ns;
    if (options_.speed > 0) origin_clock_ns_ = clock_.Now();
  }
  latest_log_ns_ = log_time_ns;
  return SaturatingDifference(log_time_ns, origin_log_ns_);
}

// Due at c0 + (t - t0) / speed, from the origin so that lateness does not accumulate.
void CanReplaySource::WaitFor(TimeNs log_offset_ns) {
  if (log_offset_ns <= 0) return;
  const double scaled_ns =
      std::min(static_cast<double>(log_offset_ns) / options_.speed, kMaxScheduleOffsetNs);
  const TimeNs deadline_ns = origin_clock_ns_ + std::llround(scaled_ns);
  if (deadline_ns <= clock_.Now()) return;
  ++stats_.sleeps;
  clock_.SleepUntil(deadline_ns);
}

}  // namespace flat2d::hal::can
