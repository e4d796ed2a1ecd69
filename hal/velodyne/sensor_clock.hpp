// Absolute time for Velodyne packets, whose timestamps count microseconds past the hour
// (VLP-16 manual 63-9243, 9.3.1.6 "Timestamp": 0 to 3,599,999,999). The minute and second
// come from the sensor, synchronised to UTC when a GPS sends PPS and $GPRMC (manual 7.4);
// the hour (and the date) must come from elsewhere. SensorClock picks the hour from, in
// order of preference:
//
//  1. GPS: a position packet whose RMC fix is valid ('A') and whose UTC time agrees with the
//     packet's own microseconds past the hour within kGpsAgreementTolerance. The agreement
//     shows that the sensor clock follows this GPS; the RMC date and hour then fix the hour,
//     and later packets follow by continuity. Host times are no longer consulted.
//  2. Host: the receive time of each data packet (kernel or pcap capture time). The host
//     clock only chooses the hour; the sub-hour time stays the sensor's, so packet jitter
//     does not leak into point times. Host and sensor must agree on elapsed time within
//     kHostStepTolerance: a single host time that disagrees is rejected (counted) and the
//     packet is resolved by continuity; two in a row that agree on a new offset mean the
//     host clock stepped (or the sensor restarted) and re-anchor the clock. A host jump of
//     whole hours leaves no trace in the sensor timestamps and is followed.
//  3. Sensor only (raw payload dumps, host time 0): continuity from the previous resolved
//     time, starting in hour 0 of the Unix epoch (1970-01-01T00).
//
// Continuity assumes less than half an hour between consecutive packets of one source.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "hal/common/time.hpp"
#include "hal/velodyne/position_packet.hpp"

namespace flat2d::hal::velodyne {

// The absolute time nearest to `reference_ns` whose offset into its UTC hour is
// `us_past_hour` (taken modulo the hour); a tie at half an hour goes to the later time.
TimeNs ResolveHourRelative(std::uint32_t us_past_hour, TimeNs reference_ns);

// Signed step in microseconds from one hour-relative device time to the next, taking the
// hour wrap the short way round (3,599,999,000 -> 500 is +1,500).
std::int64_t DeviceStepUs(std::uint32_t previous_us_past_hour, std::uint32_t us_past_hour);

enum class TimeSource : std::uint8_t { kGps, kHost, kSensorOnly };

// "gps", "host", "sensor-only".
std::string_view TimeSourceName(TimeSource source);

struct SensorClockStats {
  std::uint64_t gps_fixes_accepted = 0;
  // RMC fixes that were void, lacked date or time, or disagreed with the sensor time.
  std::uint64_t gps_fixes_rejected = 0;
  // Host times that disagreed with the sensor clock's elapsed time (packet resolved by
  // continuity instead). Under GPS host times are not consulted and never counted.
  std::uint64_t host_times_rejected = 0;
  // Confirmed host clock steps or sensor restarts after which the host re-anchored the hour.
  std::uint64_t host_reanchors = 0;
};

class SensorClock {
 public:
  // The RMC time is that of a past PPS second and the sentence arrives later, so position
  // packets run ahead of their fix: by 0.34-0.73 s in the MRPT VLP-16 capture and by
  // 0.85-1.85 s in both HDL-32E captures of the shared data. 3 s leaves a margin.
  static constexpr TimeNs kGpsAgreementTolerance = 3 * kNsPerSecond;
  // Larger than capture jitter and bursts (milliseconds) and an hour of 50 ppm drift (0.2 s).
  static constexpr TimeNs kHostStepTolerance = 5 * kNsPerSecond;

  // Uses the packet's RMC fix, if any, to anchor the hour (source kGps from then on).
  // Packets without an RMC sentence are ignored.
  void ObservePositionPacket(const PositionPacket& packet);

  // Absolute Unix-epoch time of a data packet timestamp; host_time_ns <= 0 means unknown.
  TimeNs Resolve(std::uint32_t us_past_hour, TimeNs host_time_ns);

  TimeSource source() const { return source_; }
  const SensorClockStats& stats() const { return stats_; }

 private:
  struct Reference {
    TimeNs reference_ns = 0;
    bool host_accepted = false;  // the host time may update the host offset
  };

  Reference ChooseReference(std::uint32_t us_past_hour, TimeNs host_time_ns);
  Reference OnHostDisagreement(std::uint32_t us_past_hour, TimeNs host_time_ns);

  TimeSource source_ = TimeSource::kSensorOnly;
  SensorClockStats stats_;
  bool has_previous_ = false;
  TimeNs last_ns_ = 0;                          // last resolved or GPS-anchored time
  std::optional<TimeNs> host_offset_ns_;        // resolved minus host time, last accepted
  std::optional<TimeNs> pending_offset_ns_;     // offset of the last rejected host time
};

}  // namespace flat2d::hal::velodyne
