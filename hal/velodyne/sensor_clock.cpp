#include "hal/velodyne/sensor_clock.hpp"

namespace flat2d::hal::velodyne {
namespace {

TimeNs Distance(TimeNs a, TimeNs b) { return a > b ? a - b : b - a; }

}  // namespace

TimeNs ResolveHourRelative(std::uint32_t us_past_hour, TimeNs reference_ns) {
  const TimeNs into_hour = static_cast<TimeNs>(us_past_hour) * kNsPerUs % kNsPerHour;
  TimeNs hour_start = reference_ns / kNsPerHour * kNsPerHour;
  if (hour_start > reference_ns) hour_start -= kNsPerHour;  // division truncates toward zero
  TimeNs candidate = hour_start + into_hour;
  // candidate - reference is in (-1 h, 1 h); move it into (-1/2 h, 1/2 h].
  if (candidate - reference_ns > kNsPerHour / 2) {
    candidate -= kNsPerHour;
  } else if (candidate - reference_ns <= -kNsPerHour / 2) {
    candidate += kNsPerHour;
  }
  return candidate;
}

std::int64_t DeviceStepUs(std::uint32_t previous_us_past_hour, std::uint32_t us_past_hour) {
  constexpr std::int64_t kUsPerHourSigned = kUsPerHour;
  std::int64_t step = (static_cast<std::int64_t>(us_past_hour) - previous_us_past_hour) % kUsPerHourSigned;
  if (step > kUsPerHourSigned / 2) step -= kUsPerHourSigned;
  if (step < -kUsPerHourSigned / 2) step += kUsPerHourSigned;
  return step;
}

std::string_view TimeSourceName(TimeSource source) {
  switch (source) {
    case TimeSource::kGps: return "gps";
    case TimeSource::kHost: return "host";
    case TimeSource::kSensorOnly: return "sensor-only";
  }
  return "unknown";
}

void SensorClock::ObservePositionPacket(const PositionPacket& packet) {
  if (!packet.rmc) return;
  const RmcFix& fix = *packet.rmc;
  if (!fix.valid || !fix.has_time) {
    ++stats_.gps_fixes_rejected;
    return;
  }
  const TimeNs packet_ns = ResolveHourRelative(packet.us_past_hour, fix.utc_time_ns);
  if (Distance(packet_ns, fix.utc_time_ns) > kGpsAgreementTolerance) {
    // The sensor clock does not follow this GPS (no PPS, or a stale sentence).
    ++stats_.gps_fixes_rejected;
    return;
  }
  ++stats_.gps_fixes_accepted;
  source_ = TimeSource::kGps;
  last_ns_ = packet_ns;
  has_previous_ = true;
}

TimeNs SensorClock::Resolve(std::uint32_t us_past_hour, TimeNs host_time_ns) {
  const Reference reference = ChooseReference(us_past_hour, host_time_ns);
  last_ns_ = ResolveHourRelative(us_past_hour, reference.reference_ns);
  has_previous_ = true;
  if (reference.host_accepted) host_offset_ns_ = last_ns_ - host_time_ns;
  return last_ns_;
}

SensorClock::Reference SensorClock::ChooseReference(std::uint32_t us_past_hour,
                                                    TimeNs host_time_ns) {
  if (source_ == TimeSource::kGps || host_time_ns <= 0) {
    // A GPS-disciplined sensor clock, or no host time: continue from the last time, or
    // start in hour 0 of the epoch.
    return {has_previous_ ? last_ns_ : static_cast<TimeNs>(us_past_hour) * kNsPerUs, false};
  }
  if (!host_offset_ns_) {
    source_ = TimeSource::kHost;
    return {host_time_ns, true};
  }
  // Where the sensor clock should be if host and sensor agree on elapsed time.
  const TimeNs expected = host_time_ns + *host_offset_ns_;
  if (Distance(ResolveHourRelative(us_past_hour, expected), expected) <= kHostStepTolerance) {
    pending_offset_ns_.reset();
    return {expected, true};
  }
  return OnHostDisagreement(us_past_hour, host_time_ns);
}

SensorClock::Reference SensorClock::OnHostDisagreement(std::uint32_t us_past_hour,
                                                       TimeNs host_time_ns) {
  const TimeNs offset = ResolveHourRelative(us_past_hour, host_time_ns) - host_time_ns;
  if (pending_offset_ns_ && Distance(offset, *pending_offset_ns_) <= kHostStepTolerance) {
    // Two host times in a row agree on the new offset: a real step, not a glitch.
    pending_offset_ns_.reset();
    ++stats_.host_reanchors;
    return {host_time_ns, true};
  }
  pending_offset_ns_ = offset;
  ++stats_.host_times_rejected;
  return {last_ns_, false};
}

}  // namespace flat2d::hal::velodyne
