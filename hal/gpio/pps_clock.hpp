// PPS clock-offset estimator: how far the host clock is from true time, and how fast it drifts.
//
// A GPS receiver's PPS pulse marks the start of each UTC second; the host stamps each pulse
// with its own clock. With T_k the true second a pulse marks and h_k its host time, the host
// clock is modelled as h = T + o + r (T - T_ref): offset o at a reference pulse plus a rate
// error r (drift, ppm). Steps, per pulse:
//  1. Label the pulse with its true second: the GPS second when the caller knows it (from
//     the NMEA sentence that follows each pulse); otherwise counted on from the previous
//     pulse through the current fit, and for the first pulse of an acquisition the nearest
//     whole second of the host time (so unlabelled offsets are only known modulo 1 s and
//     are reported within +-0.5 s).
//  2. Gate it: a pulse whose label does not advance, or whose host time is farther from
//     the fit's prediction than residual_gate_ns (interval_tolerance_ns from whole seconds
//     before a fit exists), is spurious: counted, not used. Labels that skip seconds count
//     the skipped pulses as missed; the pulse itself is used.
//  3. Fit o and r by least squares over a fixed window of the last accepted pulses
//     (ordinary linear regression of o_k = h_k - T_k on T_k); jitter is the rms residual.
//  4. Restart acquisition (clear the window, relabel) when no pulse was accepted for
//     lost_timeout_ns, or after max_consecutive_rejects spurious pulses in a row: the anchor
//     was wrong (a spurious first pulse) or the host clock stepped.
// Status: no PPS (no pulse yet), acquiring, locked (lock_pulses in the window and jitter
// below max_locked_jitter_ns), lost (no accepted pulse for lost_timeout_ns); the last fit is
// still reported when lost (holdover). Memory is fixed: a window of kPpsMaxWindow pulses.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::gpio {

inline constexpr int kPpsMaxWindow = 64;

struct PpsClockOptions {
  // Pulses in the least-squares window (3..kPpsMaxWindow). Longer windows average out more
  // jitter but follow drift changes (temperature) more slowly.
  int window_pulses = 32;
  // Accepted pulses in the window before the estimate is locked (3..window_pulses).
  int lock_pulses = 8;
  // Locked also needs the fit's rms residual at most this (interrupt latency jitter is
  // typically 1-20 us on embedded Linux).
  TimeNs max_locked_jitter_ns = 50'000;
  // Before a fit exists, how far an interval may be from whole seconds: crystal error
  // (100 ppm = 100 us per second) plus interrupt latency, with margin.
  TimeNs interval_tolerance_ns = 1'000'000;
  // Once fitted, how far a pulse may be from the fit's prediction.
  TimeNs residual_gate_ns = 100'000;
  // Without an accepted pulse for this long the status is lost.
  TimeNs lost_timeout_ns = 3 * kNsPerSecond;
  // This many spurious pulses in a row restart acquisition on the last of them.
  int max_consecutive_rejects = 3;
};

// Configuration errors name the field.
Status ValidatePpsClockOptions(const PpsClockOptions& options);

enum class PpsStatus : std::uint8_t { kNoPps, kAcquiring, kLocked, kLost };

// "no-pps", "acquiring", "locked", "lost".
std::string_view PpsStatusName(PpsStatus status);

enum class PulseVerdict : std::uint8_t {
  kAnchored,  // first pulse of an acquisition (also after a restart)
  kAccepted,  // used in the fit
  kSpurious,  // not used
};

struct PulseResult {
  PulseVerdict verdict = PulseVerdict::kSpurious;
  std::int64_t second = 0;  // the true second the pulse was labelled with (0 if spurious)
  std::int64_t missed = 0;  // pulses skipped since the previous accepted one
  double residual_ns = 0;   // host time minus the prediction before this pulse (0 if none)
};

struct PpsCounters {
  std::uint64_t accepted = 0;  // anchors included
  std::uint64_t missed = 0;
  std::uint64_t spurious = 0;
  std::uint64_t restarts = 0;  // acquisitions after the first
};

struct PpsEstimate {
  PpsStatus status = PpsStatus::kNoPps;
  // A fit exists (two or more pulses): offset and drift mean something. Kept when lost.
  bool valid = false;
  // Host clock minus true time at the query time (extrapolated with the drift).
  TimeNs offset_ns = 0;
  // Host clock rate error: positive when the host clock runs fast.
  double drift_ppm = 0;
  // Rms residual of the fit (0 with fewer than three pulses).
  double jitter_ns = 0;
  int window_pulses = 0;
  TimeNs last_pulse_host_ns = 0;  // last accepted pulse
  PpsCounters counters;
};

class PpsClock {
 public:
  static Result<PpsClock> Create(const PpsClockOptions& options);

  // A pulse at host time `host_ns` marking a whole second of true time.
  PulseResult AddPulse(TimeNs host_ns);
  // A pulse the caller knows marks true second `utc_second` (seconds since the Unix epoch).
  PulseResult AddPulse(TimeNs host_ns, std::int64_t utc_second);

  PpsEstimate Estimate(TimeNs now_host_ns) const;

  // True time at host time `host_ns` by the current fit; nullopt before a fit exists.
  std::optional<TimeNs> ToTrueTime(TimeNs host_ns) const;

  // Forgets all pulses and counters.
  void Reset();

 private:
  struct Pulse {
    std::int64_t second = 0;
    TimeNs host_ns = 0;
  };
  // o(T) = ref_offset_ns + intercept_ns + slope * (T - ref_second), T in seconds, o in ns.
  struct Fit {
    std::int64_t ref_second = 0;
    TimeNs ref_offset_ns = 0;
    double intercept_ns = 0;
    double slope_ns_per_s = 0;
    double jitter_ns = 0;
  };

  explicit PpsClock(const PpsClockOptions& options) : options_(options) {}

  PulseResult Process(TimeNs host_ns, std::optional<std::int64_t> utc_second);
  PulseResult Anchor(TimeNs host_ns, std::optional<std::int64_t> utc_second);
  std::int64_t LabelFromPrevious(TimeNs host_ns) const;
  double PredictOffsetNs(std::int64_t second) const;
  void Push(std::int64_t second, TimeNs host_ns);
  void Refit();

  PpsClockOptions options_;
  std::array<Pulse, kPpsMaxWindow> window_{};  // ring: the last window_pulses accepted
  int count_ = 0;  // 0 only before the first pulse: every acquisition starts with its anchor
  int next_ = 0;
  Pulse last_{};  // the newest accepted pulse
  std::optional<Fit> fit_;
  int consecutive_rejects_ = 0;
  PpsCounters counters_;
};

}  // namespace flat2d::hal::gpio
