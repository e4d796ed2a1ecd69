#include "hal/gpio/pps_clock.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace flat2d::hal::gpio {
namespace {

// Labels beyond this would overflow second * 1e9 in TimeNs (year 2262).
constexpr std::int64_t kMaxAbsSecond = std::numeric_limits<TimeNs>::max() / kNsPerSecond - 1;

// a / b rounded to nearest (ties up), for b > 0 and either sign of a.
std::int64_t RoundDiv(std::int64_t a, std::int64_t b) {
  std::int64_t quotient = a / b;
  std::int64_t remainder = a % b;
  if (remainder < 0) {
    remainder += b;
    --quotient;
  }
  return 2 * remainder >= b ? quotient + 1 : quotient;
}

TimeNs OffsetSampleNs(std::int64_t second, TimeNs host_ns) {
  return host_ns - second * kNsPerSecond;
}

Status FieldError(const char* field, const std::string& requirement, std::int64_t value) {
  return MakeError(std::string("pps_clock.") + field + " must be " + requirement + ", got " +
                   std::to_string(value));
}

}  // namespace

Status ValidatePpsClockOptions(const PpsClockOptions& options) {
  if (options.window_pulses < 3 || options.window_pulses > kPpsMaxWindow) {
    return FieldError("window_pulses", "in 3.." + std::to_string(kPpsMaxWindow),
                      options.window_pulses);
  }
  if (options.lock_pulses < 3 || options.lock_pulses > options.window_pulses) {
    return FieldError("lock_pulses", "in 3..window_pulses", options.lock_pulses);
  }
  if (options.max_locked_jitter_ns <= 0) {
    return FieldError("max_locked_jitter_ns", "positive", options.max_locked_jitter_ns);
  }
  // Above half a second a spurious pulse could pass for a real one.
  if (options.interval_tolerance_ns <= 0 || options.interval_tolerance_ns >= kNsPerSecond / 2) {
    return FieldError("interval_tolerance_ns", "in (0, 0.5 s)", options.interval_tolerance_ns);
  }
  if (options.residual_gate_ns <= 0 || options.residual_gate_ns >= kNsPerSecond / 2) {
    return FieldError("residual_gate_ns", "in (0, 0.5 s)", options.residual_gate_ns);
  }
  if (options.lost_timeout_ns <= kNsPerSecond) {
    return FieldError("lost_timeout_ns", "over 1 s", options.lost_timeout_ns);
  }
  if (options.max_consecutive_rejects < 1) {
    return FieldError("max_consecutive_rejects", "at least 1", options.max_consecutive_rejects);
  }
  return {};
}

std::string_view PpsStatusName(PpsStatus status) {
  switch (status) {
    case PpsStatus::kNoPps: return "no-pps";
    case PpsStatus::kAcquiring: return "acquiring";
    case PpsStatus::kLocked: return "locked";
    case PpsStatus::kLost: return "lost";
  }
  return "unknown";
}

Result<PpsClock> PpsClock::Create(const PpsClockOptions& options) {
  if (Status valid = ValidatePpsClockOptions(options); !valid.ok()) return valid.error();
  return PpsClock(options);
}

PulseResult PpsClock::AddPulse(TimeNs host_ns) { return Process(host_ns, std::nullopt); }

PulseResult PpsClock::AddPulse(TimeNs host_ns, std::int64_t utc_second) {
  return Process(host_ns, utc_second);
}

void PpsClock::Reset() { *this = PpsClock(options_); }

PulseResult PpsClock::Process(TimeNs host_ns, std::optional<std::int64_t> utc_second) {
  if (utc_second && (*utc_second < -kMaxAbsSecond || *utc_second > kMaxAbsSecond)) {
    ++counters_.spurious;
    return {};
  }
  if (count_ == 0) return Anchor(host_ns, utc_second);
  if (host_ns - last_.host_ns > options_.lost_timeout_ns) {
    ++counters_.restarts;
    return Anchor(host_ns, utc_second);
  }
  const std::int64_t second = utc_second.value_or(LabelFromPrevious(host_ns));
  bool plausible = second > last_.second;
  double residual_ns = 0;
  if (plausible) {
    residual_ns = static_cast<double>(OffsetSampleNs(second, host_ns)) - PredictOffsetNs(second);
    const TimeNs gate = fit_ ? options_.residual_gate_ns : options_.interval_tolerance_ns;
    plausible = std::abs(residual_ns) <= static_cast<double>(gate);
  }
  if (!plausible) {
    if (consecutive_rejects_ + 1 >= options_.max_consecutive_rejects) {
      ++counters_.restarts;
      return Anchor(host_ns, utc_second);
    }
    ++consecutive_rejects_;
    ++counters_.spurious;
    return {PulseVerdict::kSpurious, 0, 0, residual_ns};
  }
  const std::int64_t missed = second - last_.second - 1;
  counters_.missed += static_cast<std::uint64_t>(missed);
  ++counters_.accepted;
  consecutive_rejects_ = 0;
  Push(second, host_ns);
  return {PulseVerdict::kAccepted, second, missed, residual_ns};
}

PulseResult PpsClock::Anchor(TimeNs host_ns, std::optional<std::int64_t> utc_second) {
  const std::int64_t second = utc_second.value_or(RoundDiv(host_ns, kNsPerSecond));
  count_ = 0;
  next_ = 0;
  fit_.reset();
  consecutive_rejects_ = 0;
  ++counters_.accepted;
  Push(second, host_ns);
  return {PulseVerdict::kAnchored, second, 0, 0};
}

// Over a gap shorter than lost_timeout_ns the offset moves by drift x gap (milliseconds even
// at 1000 ppm), far from the half second that would mislabel a pulse.
std::int64_t PpsClock::LabelFromPrevious(TimeNs host_ns) const {
  const TimeNs true_ns = host_ns - std::llround(PredictOffsetNs(last_.second));
  return RoundDiv(true_ns, kNsPerSecond);
}

double PpsClock::PredictOffsetNs(std::int64_t second) const {
  if (!fit_) return static_cast<double>(OffsetSampleNs(last_.second, last_.host_ns));
  return static_cast<double>(fit_->ref_offset_ns) + fit_->intercept_ns +
         fit_->slope_ns_per_s * static_cast<double>(second - fit_->ref_second);
}

void PpsClock::Push(std::int64_t second, TimeNs host_ns) {
  window_[static_cast<std::size_t>(next_)] = {second, host_ns};
  next_ = (next_ + 1) % options_.window_pulses;
  if (count_ < options_.window_pulses) ++count_;
  last_ = {second, host_ns};
  Refit();
}

// Ordinary least squares of the offset samples on time, both relative to the newest pulse so
// the doubles hold nanoseconds exactly.
void PpsClock::Refit() {
  if (count_ < 2) {
    fit_.reset();
    return;
  }
  const TimeNs ref_offset = OffsetSampleNs(last_.second, last_.host_ns);
  double sum_x = 0;
  double sum_y = 0;
  for (int i = 0; i < count_; ++i) {
    const Pulse& p = window_[static_cast<std::size_t>(i)];
    sum_x += static_cast<double>(p.second - last_.second);
    sum_y += static_cast<double>(OffsetSampleNs(p.second, p.host_ns) - ref_offset);
  }
  const double n = count_;
  const double mean_x = sum_x / n;
  const double mean_y = sum_y / n;
  double sxx = 0;
  double sxy = 0;
  for (int i = 0; i < count_; ++i) {
    const Pulse& p = window_[static_cast<std::size_t>(i)];
    const double dx = static_cast<double>(p.second - last_.second) - mean_x;
    const double dy =
        static_cast<double>(OffsetSampleNs(p.second, p.host_ns) - ref_offset) - mean_y;
    sxx += dx * dx;
    sxy += dx * dy;
  }
  Fit fit;
  fit.ref_second = last_.second;
  fit.ref_offset_ns = ref_offset;
  fit.slope_ns_per_s = sxy / sxx;  // sxx > 0: the window's seconds are distinct
  fit.intercept_ns = mean_y - fit.slope_ns_per_s * mean_x;
  double sum_squares = 0;
  for (int i = 0; i < count_; ++i) {
    const Pulse& p = window_[static_cast<std::size_t>(i)];
    const double x = static_cast<double>(p.second - last_.second);
    const double y = static_cast<double>(OffsetSampleNs(p.second, p.host_ns) - ref_offset);
    const double r = y - (fit.intercept_ns + fit.slope_ns_per_s * x);
    sum_squares += r * r;
  }
  fit.jitter_ns = count_ >= 3 ? std::sqrt(sum_squares / (n - 2)) : 0;
  fit_ = fit;
}

// Inverts h = T + o(T) for T, o linear in T (see Fit).
std::optional<TimeNs> PpsClock::ToTrueTime(TimeNs host_ns) const {
  if (!fit_) return std::nullopt;
  const TimeNs ref_true_ns = fit_->ref_second * kNsPerSecond;
  const double excess_ns =
      static_cast<double>(host_ns - ref_true_ns - fit_->ref_offset_ns) - fit_->intercept_ns;
  const double rate = 1.0 + fit_->slope_ns_per_s / static_cast<double>(kNsPerSecond);
  return ref_true_ns + static_cast<TimeNs>(std::llround(excess_ns / rate));
}

PpsEstimate PpsClock::Estimate(TimeNs now_host_ns) const {
  PpsEstimate estimate;
  estimate.counters = counters_;
  estimate.window_pulses = count_;
  estimate.last_pulse_host_ns = last_.host_ns;
  if (count_ == 0) {
    estimate.status = PpsStatus::kNoPps;
  } else if (now_host_ns - last_.host_ns > options_.lost_timeout_ns) {
    estimate.status = PpsStatus::kLost;
  } else if (count_ >= options_.lock_pulses && fit_ &&
             fit_->jitter_ns <= static_cast<double>(options_.max_locked_jitter_ns)) {
    estimate.status = PpsStatus::kLocked;
  } else {
    estimate.status = PpsStatus::kAcquiring;
  }
  if (const std::optional<TimeNs> true_ns = ToTrueTime(now_host_ns)) {
    estimate.valid = true;
    estimate.offset_ns = now_host_ns - *true_ns;
    estimate.drift_ppm = fit_->slope_ns_per_s / 1e3;  // 1 ppm = 1000 ns per second
    estimate.jitter_ns = fit_->jitter_ns;
  }
  return estimate;
}

}  // namespace flat2d::hal::gpio
