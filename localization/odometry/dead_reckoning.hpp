// Dead reckoning on SE(2): CAN odometry measurements in, local_T_vehicle with covariance out.
//
// The vehicle frame's origin is the rear-axle centre (x forward, y left); the local frame is
// the vehicle frame at the first measurement. Rigid body, no wheel slip. Per measurement:
//  1. Reject non-finite values; drop times before the last one (never integrate backwards);
//     merge a measurement at the last time into the held inputs without a step.
//  2. Hold the newest value of each input (wheel speeds, vehicle speed, yaw rate), since
//     vehicles send them in different frames at different rates. An input older than
//     max_gap_ns is stale. Sources, chosen at the start of each step:
//       wheels (rear):  v = (v_rl + v_rr) / 2,  w_wheels = (v_rr - v_rl) / track     (D1, D2)
//       front wheels roll along their steered direction at |(v -+ w track/2, w base)|,
//       so kAll takes their longitudinal part sign(s) sqrt(s^2 - (w base)^2)           (D3)
//       yaw-rate sensor: w = w_sensor - bias, preferred over D2 while it is fresh      (D4)
//     speed from the wheels, else from vehicle_speed_mps.
//  3. Inputs over the step [t0, t1]: zero-order hold u = u(t0), or midpoint
//     u = (u(t0) + u(t1)) / 2 (second order for smoothly varying inputs).               (D5)
//  4. Exact arc: vehicle0_T_vehicle1 = Arc(v dt, w dt) (se2.hpp E1), exact for constant
//     v and w whatever the rate; standing still (|v| below standstill_speed_mps at both
//     ends) is no motion and no noise: a parked car does not turn, whatever the gyro says. (D6)
//  5. Covariance: P1 = J_a P0 J_a^T + J_b Q J_b^T (se2.hpp E5), step covariance
//     Q = A diag(q_v dt, q_w dt) A^T with A = ArcJacobian (E7), q the variance densities
//     of white noise on v and w: q_v = speed_noise^2 or wheel_noise^2 / n_wheels,
//     q_w = yaw_rate_noise^2 or 2 wheel_noise^2 / track^2 (D2's variance).             (D7)
//  6. A step longer than max_gap_ns is counted and, per gap_policy, held (no motion) or
//     extrapolated (D5 zero-order hold of the last inputs); either way it is marked a
//     discontinuity, as is a step without a usable speed or yaw rate (pose held).
//  7. Optional bias estimation: yaw-rate samples taken after standing still for
//     standstill_settle_ns update  W = min(W + dt, tau),  bias += (w_sensor - bias) dt / W,
//     a running mean that turns into an exponential average of time constant tau.      (D8)
// No memory is allocated: the state is a handful of scalars and fixed-size matrices.
#pragma once

#include <cstdint>
#include <optional>

#include "hal/can/odometry_measurement.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "localization/odometry/odometry_sample.hpp"

namespace flat2d::localization {

enum class SpeedWheels : std::uint8_t { kRear, kAll };
enum class GapPolicy : std::uint8_t { kHold, kExtrapolate };
enum class InputHold : std::uint8_t { kZeroOrder, kMidpoint };

struct DeadReckoningOptions {
  double wheel_base_m = 2.7;       // rear to front axle; used by D3 only
  double track_m = 1.6;            // between the rear wheels' contact centres (D1, D2)
  double wheel_speed_scale = 1.0;  // multiplies every wheel speed: tyre radius calibration
  SpeedWheels speed_wheels = SpeedWheels::kRear;  // wheels averaged for v (D1 or D1 + D3)
  InputHold input_hold = InputHold::kMidpoint;    // D5

  // Noise densities of white noise on the inputs (D7): the standard deviation of what
  // they integrate to grows as density * sqrt(seconds).
  double speed_noise_m_per_sqrt_s = 0.02;        // vehicle_speed_mps
  double wheel_speed_noise_m_per_sqrt_s = 0.02;  // each wheel speed
  double yaw_rate_noise_rad_per_sqrt_s = 0.001;  // yaw-rate sensor (angle random walk)

  double yaw_rate_bias_radps = 0.0;     // subtracted from the sensor (D4); initial estimate
  bool estimate_yaw_rate_bias = false;  // D8
  double standstill_speed_mps = 0.01;   // |v| below this is standing still (D6); 0: never
  TimeNs standstill_settle_ns = 500 * kNsPerMs;  // rocking after stopping is not bias (D8)
  double bias_time_constant_s = 60.0;            // tau of D8: follows slow (thermal) bias drift

  TimeNs max_gap_ns = 200 * kNsPerMs;  // longer steps are gaps; older inputs are stale
  GapPolicy gap_policy = GapPolicy::kHold;
};

// Errors name the offending field.
Status ValidateOptions(const DeadReckoningOptions& options);

struct DeadReckoningStats {
  std::uint64_t steps = 0;                 // samples produced after the first, including held ones
  std::uint64_t duplicate_times = 0;       // at the last time: inputs merged, no step
  std::uint64_t out_of_order = 0;          // before the last time: dropped
  std::uint64_t non_finite = 0;            // NaN or infinite values: dropped
  std::uint64_t gaps = 0;                  // steps longer than max_gap_ns
  std::uint64_t steps_without_input = 0;   // no fresh speed or yaw rate: pose held
  std::uint64_t standstill_steps = 0;      // D6: no motion
  std::uint64_t wheel_yaw_rate_steps = 0;  // yaw rate from D2 (no fresh yaw-rate sensor)
  std::uint64_t bias_updates = 0;          // D8 samples
};

enum class UpdateStatus : std::uint8_t {
  kInitialized,  // first measurement: sample at the identity pose
  kStepped,      // a new sample (check sample.discontinuity)
  kMerged,       // duplicate time: inputs merged, sample unchanged
  kOutOfOrder,   // dropped
  kNonFinite,    // dropped
};

struct DeadReckoningUpdate {
  UpdateStatus status = UpdateStatus::kNonFinite;
  OdometrySample sample;  // the latest sample, new or not
  bool new_sample() const {
    return status == UpdateStatus::kInitialized || status == UpdateStatus::kStepped;
  }
};

class DeadReckoning {
 public:
  static Result<DeadReckoning> Create(const DeadReckoningOptions& options);

  DeadReckoningUpdate Update(const hal::can::OdometryMeasurement& measurement);

  const OdometrySample& latest() const { return sample_; }
  bool initialized() const { return initialized_; }
  double yaw_rate_bias_radps() const { return bias_radps_; }  // configured or estimated
  const DeadReckoningStats& stats() const { return stats_; }

 private:
  // The newest value of one input and when it arrived.
  struct Held {
    double value = 0.0;
    TimeNs time_ns = 0;
    bool valid = false;
  };
  enum class Source : std::uint8_t { kNone, kWheels, kVehicleSpeed, kYawRateSensor };
  struct Sources {
    Source speed = Source::kNone;
    Source yaw_rate = Source::kNone;
  };
  // Speed and yaw rate at one end of a step, with their variance densities (D7).
  struct Inputs {
    double v = 0.0;
    double w = 0.0;
    double q_v = 0.0;
    double q_w = 0.0;
  };

  explicit DeadReckoning(const DeadReckoningOptions& options);

  void Merge(const hal::can::OdometryMeasurement& measurement);
  void MergeWheels(const hal::can::WheelSpeeds& wheels, TimeNs time_ns,
                   const std::optional<double>& yaw_rate_radps);
  void UpdateStandstill(TimeNs time_ns);
  void UpdateBias(double yaw_rate_radps, TimeNs time_ns);
  bool Fresh(const Held& held, TimeNs now_ns) const;
  Sources ChooseSources(TimeNs now_ns) const;
  Inputs Read(Sources sources) const;
  void Step(Sources sources, const Inputs& start, const Inputs& end, TimeNs time_ns);
  void Integrate(const Inputs& inputs, double dt_s);

  DeadReckoningOptions options_;
  DeadReckoningStats stats_;
  OdometrySample sample_;
  bool initialized_ = false;
  double bias_radps_ = 0.0;
  double bias_weight_s_ = 0.0;  // W of D8
  Held wheel_speed_;            // v of D1 (and D3)
  Held wheel_yaw_rate_;         // D2
  Held vehicle_speed_;
  Held yaw_rate_sensor_;  // raw, bias not removed
  std::optional<TimeNs> standstill_since_ns_;
};

}  // namespace flat2d::localization
