// What the vehicle's CAN bus says about its motion at one instant, in SI units, after
// the configured signal mapping (odometry_mapping.hpp) has picked and scaled the signals.
// Every quantity is optional: vehicles report different subsets, at different rates.
#pragma once

#include <optional>

#include "hal/common/time.hpp"

namespace flat2d::hal::can {

struct WheelSpeeds {
  // Signed longitudinal speeds of each wheel's contact point, metres per second, forward
  // positive. Vehicles that report unsigned speeds get their sign from the gear, if mapped.
  double front_left_mps = 0.0;
  double front_right_mps = 0.0;
  double rear_left_mps = 0.0;
  double rear_right_mps = 0.0;
};

struct OdometryMeasurement {
  TimeNs time_ns = 0;
  std::optional<WheelSpeeds> wheel_speeds;
  std::optional<double> vehicle_speed_mps;   // forward positive
  std::optional<double> yaw_rate_radps;      // counter-clockwise (left turn) positive
  std::optional<double> steering_angle_rad;  // road-wheel angle, left positive
};

}  // namespace flat2d::hal::can
