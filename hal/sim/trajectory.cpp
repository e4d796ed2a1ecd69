#include "hal/sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hal/sim/drive_path.hpp"
#include "hal/sim/speed_profile.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kGroundSpacingM = 0.05;
constexpr double kDefaultAccelMps2 = 1.0;
constexpr double kDefaultLateralAccelMps2 = 2.0;

// The body's attitude from the ground under its wheels.
struct GroundPose {
  double z = 0.0;        // under the middle of the rear axle
  double pitch = 0.0;    // nose up, radians
  double roll = 0.0;     // left side up, radians
};

GroundPose PoseOnGround(const GroundHeightFn& ground, const PathPoint& point,
                        const VehicleGeometry& geometry) {
  const Eigen::Vector2d forward(std::cos(point.heading), std::sin(point.heading));
  const Eigen::Vector2d left(-forward.y(), forward.x());
  const Eigen::Vector2d half_track = 0.5 * geometry.track_m * left;
  const Eigen::Vector2d front = point.position + geometry.wheelbase_m * forward;
  auto height = [&](const Eigen::Vector2d& p) { return ground(p.x(), p.y()); };
  const double rear_left = height(point.position + half_track);
  const double rear_right = height(point.position - half_track);
  const double front_left = height(front + half_track);
  const double front_right = height(front - half_track);
  GroundPose pose;
  pose.z = 0.5 * (rear_left + rear_right);
  pose.pitch = std::atan2(0.5 * (front_left + front_right) - pose.z, geometry.wheelbase_m);
  pose.roll = std::atan2(0.5 * (rear_left + front_left) - 0.5 * (rear_right + front_right),
                         geometry.track_m);
  return pose;
}

// Rz(yaw) * Ry(-pitch) * Rx(roll) written out (nose-up pitch is a negative turn about y),
// from the heading's (cos, sin). At() runs per LiDAR firing: no trigonometry on level ground.
Eigen::Matrix3d BodyRotation(const Eigen::Vector2d& heading, double pitch, double roll) {
  const double cz = heading.x(), sz = heading.y();
  const double cy = pitch == 0.0 ? 1.0 : std::cos(pitch);
  const double sy = pitch == 0.0 ? 0.0 : -std::sin(pitch);
  const double cx = roll == 0.0 ? 1.0 : std::cos(roll);
  const double sx = roll == 0.0 ? 0.0 : std::sin(roll);
  Eigen::Matrix3d r;
  r << cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx,  //
      sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx,   //
      -sy, cy * sx, cy * cx;
  return r;
}

Status CheckGeometry(const VehicleGeometry& g, const std::string& label) {
  const double values[] = {g.wheelbase_m, g.track_m, g.wheel_radius_m, g.steering_ratio,
                           g.length_m, g.width_m};
  for (const double value : values) {
    if (!std::isfinite(value) || value <= 0.0) {
      return MakeError(label + "vehicle geometry needs positive sizes");
    }
  }
  if (!std::isfinite(g.rear_overhang_m) || g.rear_overhang_m < 0.0) {
    return MakeError(label + "vehicle rear_overhang_m must be >= 0");
  }
  return Status::Ok();
}

double OrDefault(double value, double fallback) { return value == 0.0 ? fallback : value; }

}  // namespace

Eigen::AlignedBox2d VehicleFootprint(const VehicleGeometry& geometry) {
  return Eigen::AlignedBox2d(
      Eigen::Vector2d(-geometry.rear_overhang_m, -0.5 * geometry.width_m),
      Eigen::Vector2d(geometry.length_m - geometry.rear_overhang_m, 0.5 * geometry.width_m));
}

struct Trajectory::Impl {
  DrivePath path;
  SpeedProfile profile;
  VehicleGeometry geometry;
  double world_time_offset_s = 0.0;
  double ground_spacing_m = 0.0;
  std::vector<GroundPose> ground;  // at i * ground_spacing_m; a loop's last is its first

  GroundPose GroundAt(double s) const;
};

GroundPose Trajectory::Impl::GroundAt(double s) const {
  const double length = path.length();
  double along = path.loop() ? std::fmod(s, length) : std::clamp(s, 0.0, length);
  if (along < 0.0) along += length;
  const double index = along / ground_spacing_m;
  const auto i = std::min(static_cast<std::size_t>(index), ground.size() - 2);
  const double f = std::clamp(index - static_cast<double>(i), 0.0, 1.0);
  const GroundPose& a = ground[i];
  const GroundPose& b = ground[i + 1];
  return GroundPose{a.z + f * (b.z - a.z), a.pitch + f * (b.pitch - a.pitch),
                    a.roll + f * (b.roll - a.roll)};
}

Result<Trajectory> Trajectory::Create(const Scene& scene, const Drive& drive,
                                      const VehicleGeometry& geometry) {
  return Create([&scene](double x, double y) { return scene.GroundHeight(x, y); }, drive,
                geometry);
}

Result<Trajectory> Trajectory::Create(const GroundHeightFn& ground_height, const Drive& drive,
                                      const VehicleGeometry& geometry) {
  const std::string label = "drive '" + drive.name() + "': ";
  if (Status status = CheckGeometry(geometry, label); !status) return status.error();
  if (!std::isfinite(drive.world_time_offset_s())) {
    return MakeError(label + "world_time_offset_s is not finite");
  }
  auto path = DrivePath::Create(drive);
  if (!path) return path.error();
  SpeedLimits limits;
  limits.cruise_mps = drive.speed_mps();
  limits.max_accel_mps2 = OrDefault(drive.max_accel_mps2(), kDefaultAccelMps2);
  limits.max_lateral_accel_mps2 =
      OrDefault(drive.max_lateral_accel_mps2(), kDefaultLateralAccelMps2);
  auto profile = SpeedProfile::Create(*path, limits, drive.name());
  if (!profile) return profile.error();

  auto impl = std::make_unique<Impl>(Impl{std::move(*path), std::move(*profile), geometry,
                                          drive.world_time_offset_s(), 0.0, {}});
  const double intervals = std::max(1.0, std::ceil(impl->path.length() / kGroundSpacingM));
  impl->ground_spacing_m = impl->path.length() / intervals;
  impl->ground.reserve(static_cast<std::size_t>(intervals) + 1);
  for (std::size_t i = 0; i <= static_cast<std::size_t>(intervals); ++i) {
    const double s = static_cast<double>(i) * impl->ground_spacing_m;
    impl->ground.push_back(PoseOnGround(ground_height, impl->path.At(s), geometry));
    if (!std::isfinite(impl->ground.back().z)) {
      return MakeError(label + "ground height is not finite at s = " + std::to_string(s) + " m");
    }
  }
  if (impl->path.loop()) impl->ground.back() = impl->ground.front();
  return Trajectory(std::move(impl));
}

Trajectory::Trajectory(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Trajectory::Trajectory(Trajectory&&) noexcept = default;
Trajectory& Trajectory::operator=(Trajectory&&) noexcept = default;
Trajectory::~Trajectory() = default;

VehicleState Trajectory::At(double drive_time_s) const {
  const PathMotion motion = impl_->profile.At(drive_time_s);
  const PathPoint point = impl_->path.At(motion.s);
  const GroundPose ground = impl_->GroundAt(motion.s);
  const VehicleGeometry& g = impl_->geometry;

  VehicleState state;
  state.drive_time_s = drive_time_s;
  state.world_T_vehicle.linear() = BodyRotation(point.direction, ground.pitch, ground.roll);
  state.world_T_vehicle.translation() =
      Eigen::Vector3d(point.position.x(), point.position.y(), ground.z);
  // Along the slope the wheels roll further than the horizontal path advances.
  state.speed_mps = ground.pitch == 0.0 ? motion.speed_mps : motion.speed_mps / std::cos(ground.pitch);
  state.yaw_rate_radps = motion.speed_mps * point.curvature;
  state.steering_angle_rad =
      point.curvature == 0.0 ? 0.0 : std::atan(g.wheelbase_m * point.curvature);
  // Rigid body in the plane: a wheel at (x, y) moves at v e_x + omega e_z x (x, y).
  const double v = state.speed_mps;
  const double omega = state.yaw_rate_radps;
  auto wheel_speed = [&](double x, double y) {
    return omega == 0.0 ? v : std::hypot(v - omega * y, omega * x);
  };
  const double half_track = 0.5 * g.track_m;
  state.wheel_speeds_mps[kFrontLeft] = wheel_speed(g.wheelbase_m, half_track);
  state.wheel_speeds_mps[kFrontRight] = wheel_speed(g.wheelbase_m, -half_track);
  state.wheel_speeds_mps[kRearLeft] = wheel_speed(0.0, half_track);
  state.wheel_speeds_mps[kRearRight] = wheel_speed(0.0, -half_track);
  return state;
}

double Trajectory::duration_s() const { return impl_->profile.duration_s(); }
double Trajectory::world_time_offset_s() const { return impl_->world_time_offset_s; }
const VehicleGeometry& Trajectory::geometry() const { return impl_->geometry; }
double Trajectory::path_length_m() const { return impl_->path.length(); }
bool Trajectory::loop() const { return impl_->path.loop(); }
double Trajectory::lap_duration_s() const { return impl_->profile.lap_duration_s(); }

}  // namespace flat2d::hal::sim
