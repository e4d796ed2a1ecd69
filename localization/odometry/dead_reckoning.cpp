#include "localization/odometry/dead_reckoning.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace flat2d::localization {
namespace {

using hal::can::OdometryMeasurement;
using hal::can::WheelSpeeds;

double Seconds(TimeNs ns) { return static_cast<double>(ns) * 1e-9; }

bool Finite(const std::optional<double>& value) { return !value || std::isfinite(*value); }

bool AllFinite(const OdometryMeasurement& m) {
  if (m.wheel_speeds) {
    const WheelSpeeds& w = *m.wheel_speeds;
    if (!std::isfinite(w.front_left_mps) || !std::isfinite(w.front_right_mps) ||
        !std::isfinite(w.rear_left_mps) || !std::isfinite(w.rear_right_mps)) {
      return false;
    }
  }
  return Finite(m.vehicle_speed_mps) && Finite(m.yaw_rate_radps) && Finite(m.steering_angle_rad);
}

// D3: the longitudinal part of a front wheel's speed, given its lateral part w * base.
double Longitudinal(double wheel_speed, double lateral_speed) {
  const double squared = wheel_speed * wheel_speed - lateral_speed * lateral_speed;
  return std::copysign(std::sqrt(std::max(squared, 0.0)), wheel_speed);
}

Status Check(bool ok, const char* field, const char* requirement, double value) {
  if (ok) return Status::Ok();
  return MakeError(std::string("DeadReckoningOptions.") + field + " must be " + requirement +
                   ", got " + std::to_string(value));
}

}  // namespace

Status ValidateOptions(const DeadReckoningOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  const char* kPositive = "positive and finite";
  const char* kNonNegative = "non-negative and finite";
  for (const Status& status : {
           Check(positive(o.wheel_base_m), "wheel_base_m", kPositive, o.wheel_base_m),
           Check(positive(o.track_m), "track_m", kPositive, o.track_m),
           Check(positive(o.wheel_speed_scale), "wheel_speed_scale", kPositive,
                 o.wheel_speed_scale),
           Check(non_negative(o.speed_noise_m_per_sqrt_s), "speed_noise_m_per_sqrt_s", kNonNegative,
                 o.speed_noise_m_per_sqrt_s),
           Check(non_negative(o.wheel_speed_noise_m_per_sqrt_s), "wheel_speed_noise_m_per_sqrt_s",
                 kNonNegative, o.wheel_speed_noise_m_per_sqrt_s),
           Check(non_negative(o.yaw_rate_noise_rad_per_sqrt_s), "yaw_rate_noise_rad_per_sqrt_s",
                 kNonNegative, o.yaw_rate_noise_rad_per_sqrt_s),
           Check(std::isfinite(o.yaw_rate_bias_radps), "yaw_rate_bias_radps", "finite",
                 o.yaw_rate_bias_radps),
           Check(non_negative(o.standstill_speed_mps), "standstill_speed_mps", kNonNegative,
                 o.standstill_speed_mps),
           Check(o.standstill_settle_ns >= 0, "standstill_settle_ns", "non-negative",
                 static_cast<double>(o.standstill_settle_ns)),
           Check(positive(o.bias_time_constant_s), "bias_time_constant_s", kPositive,
                 o.bias_time_constant_s),
           Check(o.max_gap_ns > 0, "max_gap_ns", "positive", static_cast<double>(o.max_gap_ns)),
       }) {
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Result<DeadReckoning> DeadReckoning::Create(const DeadReckoningOptions& options) {
  if (Status status = ValidateOptions(options); !status.ok()) return status.error();
  return DeadReckoning(options);
}

DeadReckoning::DeadReckoning(const DeadReckoningOptions& options)
    : options_(options), bias_radps_(options.yaw_rate_bias_radps) {}

DeadReckoningUpdate DeadReckoning::Update(const OdometryMeasurement& measurement) {
  if (!AllFinite(measurement)) {
    ++stats_.non_finite;
    return {UpdateStatus::kNonFinite, sample_};
  }
  if (!initialized_) {
    Merge(measurement);
    initialized_ = true;
    sample_ = OdometrySample{};
    sample_.time_ns = measurement.time_ns;
    return {UpdateStatus::kInitialized, sample_};
  }
  if (measurement.time_ns < sample_.time_ns) {
    ++stats_.out_of_order;
    return {UpdateStatus::kOutOfOrder, sample_};
  }
  if (measurement.time_ns == sample_.time_ns) {
    // A second frame stamped alike (often another signal of the same instant): no step.
    ++stats_.duplicate_times;
    Merge(measurement);
    return {UpdateStatus::kMerged, sample_};
  }
  const Sources sources = ChooseSources(sample_.time_ns);
  const Inputs start = Read(sources);
  Merge(measurement);
  const Inputs end = Read(sources);
  Step(sources, start, end, measurement.time_ns);
  return {UpdateStatus::kStepped, sample_};
}

void DeadReckoning::Merge(const OdometryMeasurement& m) {
  if (m.wheel_speeds) MergeWheels(*m.wheel_speeds, m.time_ns, m.yaw_rate_radps);
  if (m.vehicle_speed_mps) vehicle_speed_ = {*m.vehicle_speed_mps, m.time_ns, true};
  UpdateStandstill(m.time_ns);
  if (m.yaw_rate_radps) {
    UpdateBias(*m.yaw_rate_radps, m.time_ns);  // before the held sample moves on
    yaw_rate_sensor_ = {*m.yaw_rate_radps, m.time_ns, true};
  }
}

void DeadReckoning::MergeWheels(const WheelSpeeds& wheels, TimeNs time_ns,
                                const std::optional<double>& yaw_rate_radps) {
  const double k = options_.wheel_speed_scale;
  const double rear_left = k * wheels.rear_left_mps;
  const double rear_right = k * wheels.rear_right_mps;
  const double wheel_yaw_rate = (rear_right - rear_left) / options_.track_m;  // D2
  wheel_yaw_rate_ = {wheel_yaw_rate, time_ns, true};
  double speed = 0.5 * (rear_left + rear_right);  // D1
  if (options_.speed_wheels == SpeedWheels::kAll) {
    double w = wheel_yaw_rate;  // D3 needs w: the sensor's when there is one
    if (yaw_rate_radps) {
      w = *yaw_rate_radps - bias_radps_;
    } else if (Fresh(yaw_rate_sensor_, time_ns)) {
      w = yaw_rate_sensor_.value - bias_radps_;
    }
    const double lateral = w * options_.wheel_base_m;
    speed = 0.25 * (rear_left + rear_right + Longitudinal(k * wheels.front_left_mps, lateral) +
                    Longitudinal(k * wheels.front_right_mps, lateral));
  }
  wheel_speed_ = {speed, time_ns, true};
}

void DeadReckoning::UpdateStandstill(TimeNs time_ns) {
  const Held* speed = Fresh(wheel_speed_, time_ns)     ? &wheel_speed_
                      : Fresh(vehicle_speed_, time_ns) ? &vehicle_speed_
                                                       : nullptr;
  if (speed == nullptr || std::abs(speed->value) >= options_.standstill_speed_mps) {
    standstill_since_ns_.reset();
  } else if (!standstill_since_ns_) {
    standstill_since_ns_ = time_ns;
  }
}

void DeadReckoning::UpdateBias(double yaw_rate_radps, TimeNs time_ns) {
  if (!options_.estimate_yaw_rate_bias || !standstill_since_ns_) return;
  if (time_ns - *standstill_since_ns_ < options_.standstill_settle_ns) return;
  // Each sample weighs the time since the previous one (D8).
  if (!Fresh(yaw_rate_sensor_, time_ns) || yaw_rate_sensor_.time_ns >= time_ns) return;
  const double dt = Seconds(time_ns - yaw_rate_sensor_.time_ns);
  bias_weight_s_ = std::min(bias_weight_s_ + dt, options_.bias_time_constant_s);
  bias_radps_ += (yaw_rate_radps - bias_radps_) * dt / bias_weight_s_;
  ++stats_.bias_updates;
}

bool DeadReckoning::Fresh(const Held& held, TimeNs now_ns) const {
  return held.valid && now_ns - held.time_ns <= options_.max_gap_ns;
}

DeadReckoning::Sources DeadReckoning::ChooseSources(TimeNs now_ns) const {
  Sources sources;
  if (Fresh(wheel_speed_, now_ns)) {
    sources.speed = Source::kWheels;
  } else if (Fresh(vehicle_speed_, now_ns)) {
    sources.speed = Source::kVehicleSpeed;
  }
  if (Fresh(yaw_rate_sensor_, now_ns)) {
    sources.yaw_rate = Source::kYawRateSensor;
  } else if (Fresh(wheel_yaw_rate_, now_ns)) {
    sources.yaw_rate = Source::kWheels;
  }
  return sources;
}

DeadReckoning::Inputs DeadReckoning::Read(Sources sources) const {
  const double wheel_q = options_.wheel_speed_noise_m_per_sqrt_s *
                         options_.wheel_speed_noise_m_per_sqrt_s;  // per wheel (D7)
  const double wheels = options_.speed_wheels == SpeedWheels::kAll ? 4.0 : 2.0;
  Inputs inputs;
  if (sources.speed == Source::kWheels) {
    inputs.v = wheel_speed_.value;
    inputs.q_v = wheel_q / wheels;
  } else if (sources.speed == Source::kVehicleSpeed) {
    inputs.v = vehicle_speed_.value;
    inputs.q_v = options_.speed_noise_m_per_sqrt_s * options_.speed_noise_m_per_sqrt_s;
  }
  if (sources.yaw_rate == Source::kYawRateSensor) {
    inputs.w = yaw_rate_sensor_.value - bias_radps_;  // D4
    inputs.q_w = options_.yaw_rate_noise_rad_per_sqrt_s * options_.yaw_rate_noise_rad_per_sqrt_s;
  } else if (sources.yaw_rate == Source::kWheels) {
    inputs.w = wheel_yaw_rate_.value;
    inputs.q_w = 2.0 * wheel_q / (options_.track_m * options_.track_m);
  }
  return inputs;
}

void DeadReckoning::Step(Sources sources, const Inputs& start, const Inputs& end, TimeNs time_ns) {
  const TimeNs dt_ns = time_ns - sample_.time_ns;
  ++stats_.steps;
  sample_.time_ns = time_ns;
  sample_.step_covariance.setZero();
  sample_.discontinuity = false;
  const bool gap = dt_ns > options_.max_gap_ns;
  if (gap) {
    ++stats_.gaps;
    sample_.discontinuity = true;
  }
  if (sources.speed == Source::kNone || sources.yaw_rate == Source::kNone) {
    ++stats_.steps_without_input;
    sample_.discontinuity = true;
    return;
  }
  if (gap && options_.gap_policy == GapPolicy::kHold) return;
  const bool zero_order = gap || options_.input_hold == InputHold::kZeroOrder;  // D5
  const auto standing = [&](double v) { return std::abs(v) < options_.standstill_speed_mps; };
  if (standing(start.v) && (zero_order || standing(end.v))) {  // D6
    ++stats_.standstill_steps;
    return;
  }
  if (sources.yaw_rate == Source::kWheels) ++stats_.wheel_yaw_rate_steps;
  if (zero_order) {
    Integrate(start, Seconds(dt_ns));
  } else {
    Integrate({0.5 * (start.v + end.v), 0.5 * (start.w + end.w), 0.5 * (start.q_v + end.q_v),
               0.5 * (start.q_w + end.q_w)},
              Seconds(dt_ns));
  }
}

void DeadReckoning::Integrate(const Inputs& inputs, double dt_s) {
  const double distance = inputs.v * dt_s;
  const double heading_change = inputs.w * dt_s;
  const Se2 step = Arc(distance, heading_change);                               // D6
  const Eigen::Matrix<double, 3, 2> a = ArcJacobian(distance, heading_change);  // E7
  const Eigen::Vector2d q(inputs.q_v * dt_s, inputs.q_w * dt_s);                // D7
  sample_.step_covariance = a * q.asDiagonal() * a.transpose();
  sample_.covariance = ComposeCovariance(sample_.local_T_vehicle, sample_.covariance, step,
                                         sample_.step_covariance);  // E5
  sample_.local_T_vehicle = sample_.local_T_vehicle * step;
}

}  // namespace flat2d::localization
