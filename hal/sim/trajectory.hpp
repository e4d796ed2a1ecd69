// The vehicle's motion along a Drive (scene.proto): a smooth path through the waypoints
// (straight segments, corners rounded to arcs), a speed profile within the acceleration
// and lateral-acceleration limits, the body following the ground (z, pitch, roll from the
// scene's ground under the wheels), and what the vehicle's sensors would measure: wheel
// speeds from the bicycle/Ackermann geometry, yaw rate, steering angle.
//
// Vehicle frame: origin on the ground below the middle of the rear axle, x forward, y left,
// z up. Drive time starts at 0 at rest on the first waypoint.
//
// Steps at Create: DrivePath (drive_path.hpp) rounds the corners, SpeedProfile
// (speed_profile.hpp) tabulates speed and time along it, and a table every ~5 cm of arc
// holds z, pitch and roll from the ground heights under the four wheels. At() then only
// looks up and interpolates: no allocation, and no reference to the Scene is kept.
// Simplifications: curvature (hence steering angle and yaw rate) steps where an arc meets
// a straight; the yaw rate is the heading rate in the horizontal plane; speed_mps and the
// wheel speeds are along the (possibly sloped) ground, i.e. horizontal speed / cos(pitch).
#pragma once

#include <array>
#include <functional>
#include <memory>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/sim/scene.hpp"

namespace flat2d::hal::sim {

struct VehicleGeometry {
  double wheelbase_m = 2.70;
  double track_m = 1.60;
  double wheel_radius_m = 0.33;
  double steering_ratio = 15.0;  // steering-wheel angle / road-wheel angle
  // The body's outline, for clearance checks and self-occlusion.
  double length_m = 4.60;
  double width_m = 1.80;
  double rear_overhang_m = 0.95;  // rear bumper behind the rear axle
};

// The body's outline in the vehicle frame (x from -rear_overhang to length - rear_overhang).
Eigen::AlignedBox2d VehicleFootprint(const VehicleGeometry& geometry);

// Ground height at (x, y) in the world frame, e.g. Scene::GroundHeight.
using GroundHeightFn = std::function<double(double x, double y)>;

enum WheelIndex { kFrontLeft = 0, kFrontRight = 1, kRearLeft = 2, kRearRight = 3 };

struct VehicleState {
  double drive_time_s = 0.0;
  Eigen::Isometry3d world_T_vehicle = Eigen::Isometry3d::Identity();
  double speed_mps = 0.0;            // forward speed of the vehicle origin (>= 0)
  double yaw_rate_radps = 0.0;       // about the vehicle's z axis
  double steering_angle_rad = 0.0;   // bicycle-model road-wheel angle, positive left
  std::array<double, 4> wheel_speeds_mps{};  // ground speed of each wheel, WheelIndex order
};

class Trajectory {
 public:
  static Result<Trajectory> Create(const Scene& scene, const Drive& drive,
                                   const VehicleGeometry& geometry = {});
  // The same over any ground (tests, flat worlds); ground_height is used only in Create.
  static Result<Trajectory> Create(const GroundHeightFn& ground_height, const Drive& drive,
                                   const VehicleGeometry& geometry = {});

  Trajectory(Trajectory&&) noexcept;
  Trajectory& operator=(Trajectory&&) noexcept;
  ~Trajectory();

  // The state at drive time t (clamped to [0, duration_s()]; a loop drive keeps going).
  // Continuous in t; allocates nothing.
  VehicleState At(double drive_time_s) const;

  // Time to reach the last waypoint and stop (one lap for a loop).
  double duration_s() const;
  double world_time_offset_s() const;
  const VehicleGeometry& geometry() const;
  // Horizontal length of the path (of one lap for a loop), metres.
  double path_length_m() const;
  bool loop() const;
  // Time of each lap after the first of a loop (0 for an open drive).
  double lap_duration_s() const;

 private:
  struct Impl;
  explicit Trajectory(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace flat2d::hal::sim
