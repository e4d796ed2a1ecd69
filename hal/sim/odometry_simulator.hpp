// The simulated vehicle's odometry on its CAN bus (issue 5, item 4): the frames of
// vehicle.dbc (vehicle_dbc.hpp) that the wheel-speed sensors, the yaw-rate sensor and the
// steering-angle sensor of a car driving a Trajectory would send, with the errors of
// odometry_noise.hpp, for can.log and for feeding CanOdometry directly.
//
// Steps: Create parses the embedded DBC, builds one MessageEncoder per message (checksum
// and rolling counter) and one schedule per message: frame k of a message is sent at
// start_epoch + phase + k / rate, on the same clock as the rest of the simulation
// (drive time 0 = start_epoch_ns). It draws the per-seed errors (wheel scale errors, gyro
// turn-on bias) from independent streams of the seed. Next returns the earliest pending
// frame (ties in the order WHEEL_SPEEDS, YAW_RATE, STEERING): it samples the Trajectory
// at the frame's drive time, applies the sensor's error model, and encodes the values
// (the gyro reports the mean rate over its sample period: the heading change since its
// previous sample, so its readings integrate to the true heading);
// the encoder rounds them to the DBC's resolution, which is the quantization. Frames come
// in time order, so a run loop can merge them with LiDAR packets by NextTime().
// Deterministic: the same trajectory, options and seed give identical frames. Nothing
// allocates after Create.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "hal/can/can_frame.hpp"
#include "hal/can/message_encoder.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/sim/odometry_noise.hpp"
#include "hal/sim/trajectory.hpp"

namespace flat2d::hal::sim {

struct OdometrySimOptions {
  TimeNs start_epoch_ns = 0;  // the time of drive time 0
  double duration_s = 0.0;    // frames in drive time [0, duration_s]; 0 = trajectory's duration

  // Rates of the three messages, and when each sends its first frame: ECUs run on their
  // own clocks, so their frames are not in phase. A phase must be below the period.
  double wheel_speeds_rate_hz = 100.0;
  double yaw_rate_rate_hz = 100.0;
  double steering_rate_hz = 50.0;
  double wheel_speeds_phase_s = 0.001;
  double yaw_rate_phase_s = 0.004;
  double steering_phase_s = 0.007;

  OdometryNoise noise = OdometryNoise::Mems();
  std::string interface_name = "can0";  // written into every frame (candump's column)
};

// Errors name the field.
Status ValidateOptions(const OdometrySimOptions& options);

class OdometrySimulator {
 public:
  // The trajectory must outlive the simulator. Errors: invalid options, or a DBC that does
  // not build (a bug: the DBC is compiled in).
  static Result<OdometrySimulator> Create(const Trajectory& trajectory, const OdometrySimOptions& options,
                                          std::uint64_t seed);

  // The time of the frame Next returns, or nullopt after the last one.
  std::optional<TimeNs> NextTime() const;
  // The next frame in time order, or nullopt when the duration is over.
  std::optional<can::CanFrame> Next();

  // The errors this seed drew, for tests and for the run's metadata.
  double gyro_turn_on_bias_radps() const { return gyro_.turn_on_bias_radps(); }
  double gyro_bias_radps() const { return gyro_.bias_radps(); }  // including the walk so far
  const std::array<double, 4>& wheel_scale_errors() const { return wheel_scale_errors_; }  // WheelIndex order

  // Values the encoders had to clamp to the DBC's range (0 unless the drive is extreme).
  std::uint64_t clamped_values() const;
  TimeNs end_time_ns() const { return end_ns_; }
  const OdometrySimOptions& options() const { return options_; }

 private:
  enum Message : int { kWheelSpeeds = 0, kYawRate = 1, kSteering = 2, kMessageCount = 3 };

  struct Schedule {
    TimeNs first_ns = 0;
    TimeNs period_ns = 0;
    std::int64_t sent = 0;  // frames so far
    TimeNs next_ns() const { return first_ns + sent * period_ns; }
  };

  // Indices of the signals each message sets, resolved once in Create.
  struct SignalIndices {
    std::array<std::size_t, 4> wheel_speeds{};
    std::size_t yaw_rate = 0, lateral_accel = 0, longitudinal_accel = 0;
    std::size_t steer_angle = 0, steer_rate = 0;
  };

  OdometrySimulator(const Trajectory& trajectory, const OdometrySimOptions& options, std::uint64_t seed,
                    std::array<can::MessageEncoder, kMessageCount> encoders, const SignalIndices& signals);

  std::optional<int> Earliest() const;
  void EncodeWheelSpeeds(const VehicleState& state);
  void EncodeYawRate(const VehicleState& state, double dt_s);
  void EncodeSteering(const VehicleState& state, double dt_s);

  const Trajectory* trajectory_;
  OdometrySimOptions options_;
  std::array<can::MessageEncoder, kMessageCount> encoders_;
  SignalIndices signals_;
  std::array<Schedule, kMessageCount> schedules_{};
  TimeNs end_ns_ = 0;

  GaussianSource wheel_noise_;
  GaussianSource steering_noise_;
  GyroErrorModel gyro_;
  std::array<double, 4> wheel_scale_errors_{};
  // The previous yaw-rate sample's heading and speed (mean yaw rate, acceleration), and the
  // previous steering sample's steering-wheel angle (steering rate).
  double previous_heading_rad_ = 0.0;
  double previous_speed_mps_ = 0.0;
  bool have_previous_yaw_sample_ = false;
  double previous_steering_wheel_rad_ = 0.0;
  bool have_previous_steering_ = false;
};

}  // namespace flat2d::hal::sim
