#include "hal/sim/odometry_noise.hpp"

#include <cmath>
#include <numbers>

#include "hal/common/angles.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kPerHour = 1.0 / 3600.0;          // deg/h -> deg/s
constexpr double kPerSqrtHour = 1.0 / 60.0;        // deg/sqrt(h) -> deg/sqrt(s)

// The car of both gyro presets: wheel speeds read 0.5 % fast (tyres 0.5 % smaller than the
// radius the ECU assumes, e.g. worn), each wheel within +-0.1 %; wheel-speed sensors of about 0.04 km/h noise; the steering-angle sensor
// 0.5 deg off centre with 0.1 deg noise.
OdometryNoise CarWithoutGyroErrors() {
  OdometryNoise noise;
  noise.wheels.scale_error = 0.005;
  noise.wheels.scale_error_sigma = 0.001;
  noise.wheels.speed_noise_mps = 0.01;
  noise.steering.offset_rad = 0.5 * kDegToRad;
  noise.steering.noise_rad = 0.1 * kDegToRad;
  return noise;
}

}  // namespace

OdometryNoise OdometryNoise::Mems() {
  OdometryNoise noise = CarWithoutGyroErrors();
  // G1 at T = 600 s: bias 2.5e-4 rad/s (52 deg/h, a residual turn-on bias of automotive
  // yaw-rate sensors) gives 0.15 rad, the rate random walk 0.042 rad and the ARW of
  // 0.5 deg/sqrt(h) 0.004 rad: RMS 0.156 rad, mean |drift| 0.125 rad (thesis 7.3.3).
  noise.gyro.bias_sigma_radps = 2.5e-4;
  noise.gyro.bias_random_walk_radps_per_sqrt_s = 5e-6;
  noise.gyro.angle_random_walk_rad_per_sqrt_s = 0.5 * kPerSqrtHour * kDegToRad;
  return noise;
}

OdometryNoise OdometryNoise::Fog() {
  OdometryNoise noise = CarWithoutGyroErrors();
  // Navigation-grade FOG: bias 0.05 deg/h, ARW 0.005 deg/sqrt(h); G1 at 600 s: 2e-4 rad.
  noise.gyro.bias_sigma_radps = 0.05 * kPerHour * kDegToRad;
  noise.gyro.bias_random_walk_radps_per_sqrt_s = 1e-8;
  noise.gyro.angle_random_walk_rad_per_sqrt_s = 0.005 * kPerSqrtHour * kDegToRad;
  return noise;
}

OdometryNoise OdometryNoise::None() { return OdometryNoise{}; }

double GaussianSource::Uniform() {
  // The top 53 bits, shifted to (0, 1] so that the logarithm below stays finite.
  return (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
}

double GaussianSource::Next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double radius = std::sqrt(-2.0 * std::log(Uniform()));
  const double angle = 2.0 * std::numbers::pi * Uniform();
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

GyroErrorModel::GyroErrorModel(const GyroNoise& noise, std::uint64_t seed)
    : noise_(noise), gaussian_(seed) {
  turn_on_bias_ = noise.bias_radps + noise.bias_sigma_radps * gaussian_.Next();
}

double GyroErrorModel::Measure(double true_rate_radps, double dt_s) {
  if (!(dt_s > 0.0)) return true_rate_radps + turn_on_bias_ + walk_;  // no time, no noise
  walk_ += noise_.bias_random_walk_radps_per_sqrt_s * std::sqrt(dt_s) * gaussian_.Next();
  const double white = noise_.angle_random_walk_rad_per_sqrt_s / std::sqrt(dt_s) * gaussian_.Next();
  return true_rate_radps + turn_on_bias_ + walk_ + white;
}

}  // namespace flat2d::hal::sim
