#include "hal/net/replay.hpp"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <optional>

namespace flat2d::hal::net {
namespace {

// Far beyond any capture (~30 years) yet safe to add to a monotonic time.
constexpr double kMaxScheduleOffsetNs = 1e18;

bool PortSelected(const ReplayOptions& options, std::uint16_t port) {
  return options.destination_ports.empty() ||
         std::find(options.destination_ports.begin(), options.destination_ports.end(), port) !=
             options.destination_ports.end();
}

bool InOutage(const ReplayOptions& options, TimeNs offset_ns) {
  return options.outage_ns > 0 && offset_ns >= options.outage_from_ns &&
         offset_ns - options.outage_from_ns < options.outage_ns;
}

// Maps capture times onto the replay clock's time line.
class Schedule {
 public:
  Schedule(const ReplayOptions& options, ReplayClock& clock) : options_(options), clock_(clock) {}

  // The capture-time offset of this datagram from the first one.
  TimeNs CaptureOffset(const UdpDatagram& datagram) {
    if (!started_) {
      started_ = true;
      first_capture_ns_ = datagram.receive_time_ns;
      untimed_ = datagram.receive_time_ns == 0;
      start_ns_ = clock_.Now();
    }
    if (untimed_) return static_cast<TimeNs>(untimed_index_++) * options_.untimed_interval_ns;
    return datagram.receive_time_ns - first_capture_ns_;
  }

  // Sleeps until the datagram at `capture_offset_ns` is due (eq. start + offset / speed).
  void WaitFor(TimeNs capture_offset_ns) {
    if (options_.speed <= 0 || capture_offset_ns <= 0) return;
    const double scaled = std::min(static_cast<double>(capture_offset_ns) / options_.speed,
                                   kMaxScheduleOffsetNs);
    const TimeNs deadline_ns = start_ns_ + std::llround(scaled);
    if (deadline_ns > clock_.Now()) clock_.SleepUntil(deadline_ns);
  }

 private:
  const ReplayOptions& options_;
  ReplayClock& clock_;
  bool started_ = false;
  TimeNs first_capture_ns_ = 0;
  bool untimed_ = false;
  std::uint64_t untimed_index_ = 0;
  TimeNs start_ns_ = 0;
};

}  // namespace

TimeNs MonotonicReplayClock::Now() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return now.tv_sec * kNsPerSecond + now.tv_nsec;
}

void MonotonicReplayClock::SleepUntil(TimeNs deadline_ns) {
  timespec deadline{};
  deadline.tv_sec = deadline_ns / kNsPerSecond;
  deadline.tv_nsec = deadline_ns % kNsPerSecond;
  // clock_nanosleep returns the error instead of setting errno; resume after signals.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

ReplayStats Replay(DatagramSource& source, DatagramSink& sink, ReplayClock& clock,
                   const ReplayOptions& options) {
  ReplayStats stats;
  Schedule schedule(options, clock);
  while (options.max_datagrams == 0 || stats.sent + stats.send_errors < options.max_datagrams) {
    const std::optional<UdpDatagram> datagram = source.Next();
    if (!datagram) break;
    if (!PortSelected(options, datagram->destination.port)) {
      ++stats.skipped;
      continue;
    }
    const TimeNs offset_ns = schedule.CaptureOffset(*datagram);
    if (options.max_duration_ns > 0 && offset_ns > options.max_duration_ns) break;
    if (InOutage(options, offset_ns)) {
      ++stats.withheld;
      continue;
    }
    schedule.WaitFor(offset_ns);
    if (Status sent = sink.Send(*datagram); sent) {
      ++stats.sent;
    } else {
      if (stats.send_errors == 0) stats.first_send_error = sent.error().message;
      ++stats.send_errors;
    }
  }
  return stats;
}

}  // namespace flat2d::hal::net
