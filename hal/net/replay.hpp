// Replaying a recorded capture to a sink with the original timing, scaled.
//
// The daemon and the tools are tested against recorded drives by sending the capture
// to the live receiver as the sensor did. Steps: (1) skip datagrams whose destination
// port is not selected (e.g. keep only 2368 data and 8308 position); (2) schedule each
// datagram at start + (capture time - first capture time) / speed on a monotonic
// clock, so a late send does not push back the ones after it, and sleep until then;
// (3) send it and count failures without stopping; (4) stop at the end of the source
// or at the count or capture-time limit. The clock is an interface so that tests can
// check the schedule without sleeping.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hal/common/time.hpp"
#include "hal/net/datagram_sink.hpp"
#include "hal/net/datagram_source.hpp"

namespace flat2d::hal::net {

class ReplayClock {
 public:
  virtual ~ReplayClock() = default;
  virtual TimeNs Now() = 0;                        // monotonic, any epoch
  virtual void SleepUntil(TimeNs deadline_ns) = 0;  // on the Now() time line

 protected:
  ReplayClock() = default;
  ReplayClock(const ReplayClock&) = default;
  ReplayClock& operator=(const ReplayClock&) = default;
};

// CLOCK_MONOTONIC with absolute-deadline sleeps (no drift from sleep overshoot).
class MonotonicReplayClock final : public ReplayClock {
 public:
  TimeNs Now() override;
  void SleepUntil(TimeNs deadline_ns) override;
};

struct ReplayOptions {
  double speed = 1.0;  // 2 replays twice as fast; <= 0 sends as fast as possible
  std::uint64_t max_datagrams = 0;  // stop after this many sends (ok or not); 0: all
  TimeNs max_duration_ns = 0;       // stop after this much capture time; 0: all
  std::vector<std::uint16_t> destination_ports;  // replay only these; empty: all
  // Sources without timestamps (raw dumps, receive_time_ns == 0) are paced at this
  // interval, e.g. 1327 us for VLP-16 data; 0 sends them as fast as possible.
  TimeNs untimed_interval_ns = 0;
  // A sensor outage: datagrams whose capture offset falls in [outage_from_ns,
  // outage_from_ns + outage_ns) are not sent, and the schedule runs on through them, so the
  // receiver hears nothing for that long and then the capture resumes on time.
  TimeNs outage_from_ns = 0;
  TimeNs outage_ns = 0;
};

struct ReplayStats {
  std::uint64_t sent = 0;
  std::uint64_t send_errors = 0;
  std::uint64_t skipped = 0;  // destination port not selected
  std::uint64_t withheld = 0;  // in the outage
  std::string first_send_error;
};

ReplayStats Replay(DatagramSource& source, DatagramSink& sink, ReplayClock& clock,
                   const ReplayOptions& options);

}  // namespace flat2d::hal::net
