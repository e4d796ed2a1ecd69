// Synthetic PPS pulse trains with a known host clock error, for the PpsClock tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>

#include "hal/gpio/pps_clock.hpp"

namespace flat2d::hal::gpio::testing {

constexpr std::int64_t kFirstSecond = 1'700'000'000;  // 2023-11-14, the first pulse's second

// A host clock that is off by offset_ns at the first pulse and runs fast by drift_ppm; each
// pulse is stamped with Gaussian jitter.
struct Truth {
  TimeNs offset_ns = 0;
  double drift_ppm = 0;
  double jitter_ns = 0;
};

inline double SinceFirstNs(TimeNs true_ns) {
  return static_cast<double>(true_ns - kFirstSecond * kNsPerSecond);
}

inline TimeNs OffsetAtNs(const Truth& truth, TimeNs true_ns) {
  return truth.offset_ns + std::llround(truth.drift_ppm * 1e-6 * SinceFirstNs(true_ns));
}

inline TimeNs IdealHostNs(const Truth& truth, TimeNs true_ns) {
  return true_ns + OffsetAtNs(truth, true_ns);
}

class PulseTrain {
 public:
  PulseTrain(const Truth& truth, std::uint32_t seed)
      : truth_(truth), rng_(seed), noise_(0.0, truth.jitter_ns > 0 ? truth.jitter_ns : 1.0) {}

  // Host time of the pulse marking second kFirstSecond + k.
  TimeNs Pulse(std::int64_t k) {
    const TimeNs ideal = IdealHostNs(truth_, (kFirstSecond + k) * kNsPerSecond);
    return truth_.jitter_ns > 0 ? ideal + std::llround(noise_(rng_)) : ideal;
  }

 private:
  Truth truth_;
  std::mt19937 rng_;
  std::normal_distribution<double> noise_;
};

inline PpsClock MakeClock(const PpsClockOptions& options = {}) {
  Result<PpsClock> clock = PpsClock::Create(options);
  EXPECT_TRUE(clock.ok()) << clock.error().message;
  return std::move(clock).value();
}

struct Errors {
  double offset_ns = 0;
  double drift_ppm = 0;
  double to_true_ns = 0;
};

// Compares the estimate half a second after pulse `last_k` with the truth.
inline Errors Check(const PpsClock& clock, const Truth& truth, std::int64_t last_k,
                    TimeNs wrap_ns = 0) {
  const TimeNs query_true = (kFirstSecond + last_k) * kNsPerSecond + kNsPerSecond / 2;
  const TimeNs query_host = IdealHostNs(truth, query_true);
  const PpsEstimate estimate = clock.Estimate(query_host);
  EXPECT_TRUE(estimate.valid);
  const std::optional<TimeNs> true_ns = clock.ToTrueTime(query_host);
  EXPECT_TRUE(true_ns.has_value());
  Errors errors;
  errors.offset_ns =
      static_cast<double>(estimate.offset_ns - (OffsetAtNs(truth, query_true) - wrap_ns));
  errors.drift_ppm = estimate.drift_ppm - truth.drift_ppm;
  errors.to_true_ns = static_cast<double>(true_ns.value_or(0) - (query_true + wrap_ns));
  return errors;
}

// 2 us jitter over a 32-pulse window: the fit's standard error is 0.7 us in offset half a
// second past the window and 0.04 ppm in drift; the bounds are about 7 sigma.
constexpr double kOffsetBoundNs = 5'000;
constexpr double kDriftBoundPpm = 0.25;
constexpr double kJitterNs = 2'000;

}  // namespace flat2d::hal::gpio::testing
