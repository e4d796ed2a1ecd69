// The errors of the simulated vehicle's odometry sensors (issue 5, item 4), and the
// seeded random sources that draw them, so a drive's CAN log is reproducible.
//
// Models (all rates in rad/s, speeds in m/s; "density" is per sqrt(second)):
//  - Wheel speed i: (1 + s_i) v_i + n, s_i = scale_error + scale_error_sigma * N(0,1)
//    drawn once (tyre radius: wear, pressure, load), n white with sigma speed_noise_mps
//    per sample; a wheel at rest reads 0 (no teeth pass the sensor). Quantization is the
//    DBC's resolution, applied by the encoder.
//  - Gyro (yaw rate): w + b0 + b(t) + n. b0 is the turn-on bias, fixed bias_radps plus
//    bias_sigma_radps * N(0,1) drawn once; b(t) a random walk (rate random walk K):
//    b += K sqrt(dt) N(0,1) at every sample; n white noise of density N (angle random
//    walk), sigma N / sqrt(dt) per sample of period dt. The open-loop heading error
//    after T seconds then has variance                                                (G1)
//      Var(e(T)) = bias_sigma^2 T^2 + K^2 T^3 / 3 + N^2 T   (+ (bias_radps T)^2 mean).
//  - Steering-wheel angle: ratio * delta + offset + white noise.
// Presets: Mems() is tuned to thesis 7.3.3 (Serafin 2017): the MAGIC 2.0 robot's MEMS
// gyro drifted up to 0.155 rad in a 10-minute traversal; with G1 its RMS drift after
// 600 s is about 0.15 rad. Fog() is a fibre-optic gyro (bias ~0.05 deg/h, ARW ~0.005
// deg/sqrt(h)): under 0.001 rad in 10 minutes. None() is error-free (quantization only).
#pragma once

#include <cstdint>
#include <random>

namespace flat2d::hal::sim {

struct WheelSpeedNoise {
  double scale_error = 0.0;        // common to the four wheels: +0.005 = reads 0.5 % fast
  double scale_error_sigma = 0.0;  // per-wheel spread around it, drawn once per seed
  double speed_noise_mps = 0.0;    // white, per sample
};

struct GyroNoise {
  double bias_radps = 0.0;        // fixed part of the turn-on bias (tests, calibrated offsets)
  double bias_sigma_radps = 0.0;  // random part, drawn once per seed
  double bias_random_walk_radps_per_sqrt_s = 0.0;  // K of G1 (rate random walk)
  double angle_random_walk_rad_per_sqrt_s = 0.0;   // N of G1 (white-noise density)
};

struct SteeringNoise {
  double offset_rad = 0.0;  // steering-wheel angle offset (sensor zero error)
  double noise_rad = 0.0;   // white, per sample, on the steering-wheel angle
};

struct OdometryNoise {
  WheelSpeedNoise wheels;
  GyroNoise gyro;
  SteeringNoise steering;

  static OdometryNoise Mems();  // passenger car with an automotive MEMS yaw-rate sensor
  static OdometryNoise Fog();   // the same car with a fibre-optic gyro
  static OdometryNoise None();  // exact values, quantized by the DBC only
};

// Standard normal numbers from a seed, the same on every platform and standard library
// (std::normal_distribution's algorithm is implementation-defined): mt19937_64 bits,
// 53-bit uniforms, Box-Muller pairs. Allocates nothing.
class GaussianSource {
 public:
  explicit GaussianSource(std::uint64_t seed) : engine_(seed) {}
  double Next();

 private:
  double Uniform();  // in (0, 1]
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// Independent streams of one seed: one per noise source, so that e.g. changing the wheel
// rate does not change the gyro's bias. splitmix64 of (seed, stream).
std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t stream);

// The gyro of G1, sampled at arbitrary intervals.
class GyroErrorModel {
 public:
  GyroErrorModel(const GyroNoise& noise, std::uint64_t seed);

  // The reading of the true rate at a sample `dt_s` after the previous one: the bias
  // walks first, then white noise of sigma N / sqrt(dt) is added.
  double Measure(double true_rate_radps, double dt_s);

  double turn_on_bias_radps() const { return turn_on_bias_; }
  double bias_radps() const { return turn_on_bias_ + walk_; }  // at the last sample

 private:
  GyroNoise noise_;
  GaussianSource gaussian_;
  double turn_on_bias_ = 0.0;
  double walk_ = 0.0;
};

}  // namespace flat2d::hal::sim
