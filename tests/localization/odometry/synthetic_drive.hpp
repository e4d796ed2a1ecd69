// Synthetic drives for the odometry tests: piecewise constant speed v and yaw rate w,
// their closed-form poses and the CAN measurements a rigid, non-slipping vehicle would
// report at each sample time (the segment active at time t is the one with start <= t).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "hal/can/odometry_measurement.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::testing {

struct Segment {
  double v_mps = 0.0;
  double w_radps = 0.0;
  double duration_s = 0.0;
};

struct Geometry {
  double track_m = 1.6;
  double wheel_base_m = 2.7;
};

// Closed form of a constant-(v, w) motion from the identity: x = v/w sin(wt),
// y = v/w (1 - cos(wt)), theta = wt; a straight line when w = 0.
inline Se2 ClosedFormArc(double v, double w, double t) {
  if (w == 0.0) return Se2(v * t, 0.0, 0.0);
  return Se2(v / w * std::sin(w * t), v / w * (1.0 - std::cos(w * t)), w * t);
}

inline Se2 ClosedFormPose(const std::vector<Segment>& segments, double t) {
  Se2 pose;
  for (const Segment& segment : segments) {
    const double in_segment = std::min(t, segment.duration_s);
    pose = pose * ClosedFormArc(segment.v_mps, segment.w_radps, in_segment);
    t -= in_segment;
    if (t <= 0.0) break;
  }
  return pose;
}

inline double Duration(const std::vector<Segment>& segments) {
  double total = 0.0;
  for (const Segment& segment : segments) total += segment.duration_s;
  return total;
}

// The segment active at t (the last one after the end); boundaries compared in ns.
inline Segment ActiveSegment(const std::vector<Segment>& segments, TimeNs t) {
  TimeNs end_ns = 0;
  for (const Segment& segment : segments) {
    end_ns += static_cast<TimeNs>(std::llround(segment.duration_s * 1e9));
    if (t < end_ns) return segment;
  }
  return segments.back();
}

// Wheel speeds of the rear-axle motion (v, w): rear wheels v -+ w track/2; front wheels
// roll along their steered direction at |(v -+ w track/2, w base)|, signed like v.
inline hal::can::WheelSpeeds WheelSpeedsFor(double v, double w, const Geometry& geometry) {
  const double left = v - 0.5 * w * geometry.track_m;
  const double right = v + 0.5 * w * geometry.track_m;
  const double lateral = w * geometry.wheel_base_m;
  hal::can::WheelSpeeds wheels;
  wheels.rear_left_mps = left;
  wheels.rear_right_mps = right;
  wheels.front_left_mps = std::copysign(std::hypot(left, lateral), left);
  wheels.front_right_mps = std::copysign(std::hypot(right, lateral), right);
  return wheels;
}

struct Sensors {
  bool wheels = true;
  bool yaw_rate = true;
  bool vehicle_speed = false;
};

inline hal::can::OdometryMeasurement MeasurementFor(TimeNs time_ns, double v, double w,
                                                    const Sensors& sensors,
                                                    const Geometry& geometry = {}) {
  hal::can::OdometryMeasurement m;
  m.time_ns = time_ns;
  if (sensors.wheels) m.wheel_speeds = WheelSpeedsFor(v, w, geometry);
  if (sensors.yaw_rate) m.yaw_rate_radps = w;
  if (sensors.vehicle_speed) m.vehicle_speed_mps = v;
  return m;
}

// Measurements of the drive at rate_hz from t = 0 to its end inclusive.
inline std::vector<hal::can::OdometryMeasurement> SampleDrive(const std::vector<Segment>& segments,
                                                              double rate_hz,
                                                              const Sensors& sensors,
                                                              const Geometry& geometry = {}) {
  const TimeNs period_ns = static_cast<TimeNs>(std::llround(1e9 / rate_hz));
  const TimeNs end_ns = static_cast<TimeNs>(std::llround(Duration(segments) * 1e9));
  std::vector<hal::can::OdometryMeasurement> drive;
  for (TimeNs t = 0; t <= end_ns; t += period_ns) {
    const Segment segment = ActiveSegment(segments, t);
    drive.push_back(MeasurementFor(t, segment.v_mps, segment.w_radps, sensors, geometry));
  }
  return drive;
}

inline double Seconds(TimeNs ns) { return static_cast<double>(ns) * 1e-9; }

inline double PositionError(const Se2& a, const Se2& b) {
  return (a.translation() - b.translation()).norm();
}

inline double HeadingError(const Se2& a, const Se2& b) {
  return std::abs(NormalizeAngle(a.theta() - b.theta()));
}

}  // namespace flat2d::localization::testing
