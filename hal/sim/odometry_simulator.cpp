#include "hal/sim/odometry_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>

#include "hal/common/angles.hpp"
#include "hal/sim/vehicle_dbc.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kMpsToKph = 3.6;
constexpr double kMaxRateHz = 1000.0;
constexpr double kMaxSteerRateDegps = 2000.0;  // STEER_RATE holds +-2047 deg/s  // a frame per millisecond: beyond any chassis ECU

// Seed streams (odometry_noise.hpp StreamSeed): one per error source.
enum Stream : std::uint64_t { kWheelScaleStream = 1, kWheelNoiseStream, kGyroStream, kSteeringStream };

constexpr std::array<const char*, 4> kWheelSignals = {"WHEEL_SPEED_FL", "WHEEL_SPEED_FR", "WHEEL_SPEED_RL",
                                                      "WHEEL_SPEED_RR"};

Status Require(bool ok, const char* field, const char* requirement, double value) {
  if (ok) return Status::Ok();
  return MakeError(std::string("OdometrySimOptions.") + field + " must be " + requirement + ", got " +
                   std::to_string(value));
}

bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

Result<std::size_t> Index(const can::MessageEncoder& encoder, const char* signal) {
  if (const auto index = encoder.IndexOf(signal)) return *index;
  return MakeError("vehicle.dbc: " + encoder.name() + " has no signal " + signal);
}

// Yaw of the vehicle's x axis in the world's horizontal plane.
double Heading(const VehicleState& state) {
  const Eigen::Matrix3d& r = state.world_T_vehicle.linear();
  return std::atan2(r(1, 0), r(0, 0));
}

TimeNs Nanoseconds(double seconds) { return static_cast<TimeNs>(std::llround(seconds * 1e9)); }

}  // namespace

Status ValidateOptions(const OdometrySimOptions& o) {
  const auto rate = [](double hz) { return std::isfinite(hz) && hz > 0.0 && hz <= kMaxRateHz; };
  const auto phase = [](double phase_s, double hz) { return NonNegative(phase_s) && phase_s * hz < 1.0; };
  const OdometryNoise& n = o.noise;
  for (const Status& status : {
           Require(NonNegative(o.duration_s), "duration_s", "non-negative and finite", o.duration_s),
           Require(rate(o.wheel_speeds_rate_hz), "wheel_speeds_rate_hz", "in (0, 1000]", o.wheel_speeds_rate_hz),
           Require(rate(o.yaw_rate_rate_hz), "yaw_rate_rate_hz", "in (0, 1000]", o.yaw_rate_rate_hz),
           Require(rate(o.steering_rate_hz), "steering_rate_hz", "in (0, 1000]", o.steering_rate_hz),
           Require(phase(o.wheel_speeds_phase_s, o.wheel_speeds_rate_hz), "wheel_speeds_phase_s",
                   "in [0, period)", o.wheel_speeds_phase_s),
           Require(phase(o.yaw_rate_phase_s, o.yaw_rate_rate_hz), "yaw_rate_phase_s", "in [0, period)",
                   o.yaw_rate_phase_s),
           Require(phase(o.steering_phase_s, o.steering_rate_hz), "steering_phase_s", "in [0, period)",
                   o.steering_phase_s),
           Require(std::isfinite(n.wheels.scale_error) && n.wheels.scale_error > -0.5 &&
                       n.wheels.scale_error < 0.5,
                   "noise.wheels.scale_error", "in (-0.5, 0.5)", n.wheels.scale_error),
           Require(NonNegative(n.wheels.scale_error_sigma) && n.wheels.scale_error_sigma < 0.1,
                   "noise.wheels.scale_error_sigma", "in [0, 0.1)", n.wheels.scale_error_sigma),
           Require(NonNegative(n.wheels.speed_noise_mps), "noise.wheels.speed_noise_mps",
                   "non-negative and finite", n.wheels.speed_noise_mps),
           Require(std::isfinite(n.gyro.bias_radps), "noise.gyro.bias_radps", "finite", n.gyro.bias_radps),
           Require(NonNegative(n.gyro.bias_sigma_radps), "noise.gyro.bias_sigma_radps",
                   "non-negative and finite", n.gyro.bias_sigma_radps),
           Require(NonNegative(n.gyro.bias_random_walk_radps_per_sqrt_s),
                   "noise.gyro.bias_random_walk_radps_per_sqrt_s", "non-negative and finite",
                   n.gyro.bias_random_walk_radps_per_sqrt_s),
           Require(NonNegative(n.gyro.angle_random_walk_rad_per_sqrt_s),
                   "noise.gyro.angle_random_walk_rad_per_sqrt_s", "non-negative and finite",
                   n.gyro.angle_random_walk_rad_per_sqrt_s),
           Require(std::isfinite(n.steering.offset_rad), "noise.steering.offset_rad", "finite",
                   n.steering.offset_rad),
           Require(NonNegative(n.steering.noise_rad), "noise.steering.noise_rad", "non-negative and finite",
                   n.steering.noise_rad),
       }) {
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Result<OdometrySimulator> OdometrySimulator::Create(const Trajectory& trajectory,
                                                    const OdometrySimOptions& options, std::uint64_t seed) {
  if (Status status = ValidateOptions(options); !status.ok()) return status.error();
  Result<can::Dbc> dbc = VehicleDbc();
  if (!dbc.ok()) return dbc.error();
  Result<can::MessageEncoder> wheels = can::MessageEncoder::Create(*dbc, kWheelSpeedsMessage);
  if (!wheels.ok()) return wheels.error();
  Result<can::MessageEncoder> yaw = can::MessageEncoder::Create(*dbc, kYawRateMessage);
  if (!yaw.ok()) return yaw.error();
  Result<can::MessageEncoder> steering = can::MessageEncoder::Create(*dbc, kSteeringMessage);
  if (!steering.ok()) return steering.error();

  SignalIndices signals;
  for (std::size_t wheel = 0; wheel < kWheelSignals.size(); ++wheel) {
    Result<std::size_t> index = Index(*wheels, kWheelSignals[wheel]);
    if (!index.ok()) return index.error();
    signals.wheel_speeds[wheel] = *index;
  }
  for (auto [encoder, name, slot] : {std::tuple{&*yaw, "YAW_RATE", &signals.yaw_rate},
                                     std::tuple{&*yaw, "LATERAL_ACCEL", &signals.lateral_accel},
                                     std::tuple{&*yaw, "LONGITUDINAL_ACCEL", &signals.longitudinal_accel},
                                     std::tuple{&*steering, "STEER_ANGLE", &signals.steer_angle},
                                     std::tuple{&*steering, "STEER_RATE", &signals.steer_rate}}) {
    Result<std::size_t> index = Index(*encoder, name);
    if (!index.ok()) return index.error();
    *slot = *index;
  }
  return OdometrySimulator(trajectory, options, seed,
                           {std::move(wheels).value(), std::move(yaw).value(), std::move(steering).value()},
                           signals);
}

OdometrySimulator::OdometrySimulator(const Trajectory& trajectory, const OdometrySimOptions& options,
                                     std::uint64_t seed, std::array<can::MessageEncoder, kMessageCount> encoders,
                                     const SignalIndices& signals)
    : trajectory_(&trajectory),
      options_(options),
      encoders_(std::move(encoders)),
      signals_(signals),
      wheel_noise_(StreamSeed(seed, kWheelNoiseStream)),
      steering_noise_(StreamSeed(seed, kSteeringStream)),
      gyro_(options.noise.gyro, StreamSeed(seed, kGyroStream)) {
  const double duration_s = options.duration_s > 0.0 ? options.duration_s : trajectory.duration_s();
  end_ns_ = options.start_epoch_ns + Nanoseconds(duration_s);
  const auto schedule = [&](double rate_hz, double phase_s) {
    return Schedule{options.start_epoch_ns + Nanoseconds(phase_s), Nanoseconds(1.0 / rate_hz), 0};
  };
  schedules_[kWheelSpeeds] = schedule(options.wheel_speeds_rate_hz, options.wheel_speeds_phase_s);
  schedules_[kYawRate] = schedule(options.yaw_rate_rate_hz, options.yaw_rate_phase_s);
  schedules_[kSteering] = schedule(options.steering_rate_hz, options.steering_phase_s);

  GaussianSource scales(StreamSeed(seed, kWheelScaleStream));
  for (double& scale : wheel_scale_errors_) {
    scale = options.noise.wheels.scale_error + options.noise.wheels.scale_error_sigma * scales.Next();
  }
}

std::optional<int> OdometrySimulator::Earliest() const {
  std::optional<int> earliest;
  for (int message = 0; message < kMessageCount; ++message) {
    const TimeNs t = schedules_[message].next_ns();
    if (t > end_ns_) continue;
    if (!earliest || t < schedules_[*earliest].next_ns()) earliest = message;
  }
  return earliest;
}

std::optional<TimeNs> OdometrySimulator::NextTime() const {
  const std::optional<int> message = Earliest();
  if (!message) return std::nullopt;
  return schedules_[*message].next_ns();
}

std::optional<can::CanFrame> OdometrySimulator::Next() {
  const std::optional<int> message = Earliest();
  if (!message) return std::nullopt;
  Schedule& schedule = schedules_[*message];
  const TimeNs time_ns = schedule.next_ns();
  const double drive_time_s = static_cast<double>(time_ns - options_.start_epoch_ns) * 1e-9;
  const double dt_s = static_cast<double>(schedule.period_ns) * 1e-9;
  const VehicleState state = trajectory_->At(drive_time_s);
  switch (*message) {
    case kWheelSpeeds: EncodeWheelSpeeds(state); break;
    case kYawRate: EncodeYawRate(state, dt_s); break;
    default: EncodeSteering(state, dt_s); break;
  }
  ++schedule.sent;
  can::CanFrame frame = encoders_[*message].Build(time_ns);
  frame.set_interface_name(options_.interface_name);
  return frame;
}

void OdometrySimulator::EncodeWheelSpeeds(const VehicleState& state) {
  const WheelSpeedNoise& noise = options_.noise.wheels;
  for (std::size_t wheel = 0; wheel < 4; ++wheel) {
    const double truth = state.wheel_speeds_mps[wheel];
    // Draw for every wheel and frame, so the stream does not depend on the motion.
    const double white = noise.speed_noise_mps * wheel_noise_.Next();
    // A wheel at rest reads 0 (no teeth pass the sensor); the signal is unsigned.
    const double measured = truth > 0.0 ? std::max(0.0, (1.0 + wheel_scale_errors_[wheel]) * truth + white) : 0.0;
    encoders_[kWheelSpeeds].Set(signals_.wheel_speeds[wheel], measured * kMpsToKph);
  }
}

void OdometrySimulator::EncodeYawRate(const VehicleState& state, double dt_s) {
  // The mean rate over the sample period, as a MEMS sensor's decimation filter gives: the
  // readings then integrate to the true heading change even where the path's curvature
  // steps (a straight meeting an arc), which instantaneous samples would alias.
  const double heading = Heading(state);
  if (!have_previous_yaw_sample_) {
    previous_heading_rad_ = Heading(trajectory_->At(std::max(0.0, state.drive_time_s - dt_s)));
    previous_speed_mps_ = state.speed_mps;
    have_previous_yaw_sample_ = true;
  }
  const double mean_yaw_rate = std::remainder(heading - previous_heading_rad_, 2.0 * std::numbers::pi) / dt_s;
  // Kinematic accelerations (no gravity): the cluster's other signals, for a plausible bus.
  const double longitudinal = (state.speed_mps - previous_speed_mps_) / dt_s;
  previous_heading_rad_ = heading;
  previous_speed_mps_ = state.speed_mps;
  can::MessageEncoder& encoder = encoders_[kYawRate];
  encoder.Set(signals_.yaw_rate, gyro_.Measure(mean_yaw_rate, dt_s) * kRadToDeg);
  encoder.Set(signals_.lateral_accel, state.speed_mps * state.yaw_rate_radps);
  encoder.Set(signals_.longitudinal_accel, longitudinal);
}

void OdometrySimulator::EncodeSteering(const VehicleState& state, double dt_s) {
  const double steering_wheel = state.steering_angle_rad * trajectory_->geometry().steering_ratio;
  const double rate = have_previous_steering_ ? (steering_wheel - previous_steering_wheel_rad_) / dt_s : 0.0;
  previous_steering_wheel_rad_ = steering_wheel;
  have_previous_steering_ = true;
  const SteeringNoise& noise = options_.noise.steering;
  const double measured = steering_wheel + noise.offset_rad + noise.noise_rad * steering_noise_.Next();
  can::MessageEncoder& encoder = encoders_[kSteering];
  encoder.Set(signals_.steer_angle, measured * kRadToDeg);
  // The path's curvature steps where arcs meet straights, so the steering wheel turns in
  // one frame there; a real sensor saturates, as this does, inside the DBC's range.
  encoder.Set(signals_.steer_rate, std::clamp(rate * kRadToDeg, -kMaxSteerRateDegps, kMaxSteerRateDegps));
}

std::uint64_t OdometrySimulator::clamped_values() const {
  std::uint64_t clamped = 0;
  for (const can::MessageEncoder& encoder : encoders_) clamped += encoder.stats().clamped;
  return clamped;
}

}  // namespace flat2d::hal::sim
