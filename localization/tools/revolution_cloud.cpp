#include "localization/tools/revolution_cloud.hpp"

namespace flat2d::localization::tools {

hal::cloud::PointCloud RevolutionCloud(const hal::velodyne::Revolution& revolution, const SensorMotion& motion) {
  hal::cloud::PointCloud cloud;
  if (revolution.fans.empty()) return cloud;
  cloud.points.reserve(static_cast<std::size_t>(revolution.points));
  const hal::velodyne::ReturnKind kind = revolution.fans.front().kind;
  for (const hal::velodyne::Fan& fan : revolution.fans) {
    if (fan.kind != kind) continue;
    // The lasers of a fan fire within 56 us: one pose per fan is 5 mm at 90 m/s.
    const Eigen::Isometry3f reference_T_sensor =
        motion ? motion(fan.stamp_ns).cast<float>() : Eigen::Isometry3f::Identity();
    for (int laser = 0; laser < fan.num_lasers; ++laser) {
      const hal::velodyne::LaserReturn& r = fan.returns[static_cast<std::size_t>(laser)];
      if (r.range_m > 0.0F) cloud.points.push_back(reference_T_sensor * r.xyz);
    }
  }
  return cloud;
}

Eigen::Isometry3d ScaledMotion(const Eigen::Isometry3d& motion, double f) {
  const Eigen::AngleAxisd rotation(motion.rotation());
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() = Eigen::AngleAxisd(rotation.angle() * f, rotation.axis()).toRotationMatrix();
  scaled.translation() = f * motion.translation();
  return scaled;
}

std::optional<Eigen::Isometry3d> OdometrySensorMotion(const maps::InterpolatedPoses& odometry,
                                                      const Eigen::Isometry3d& vehicle_T_sensor, TimeNs t0, TimeNs t) {
  const auto from = odometry.PoseAt(t0), to = odometry.PoseAt(t);
  if (!from || !to) return std::nullopt;
  return vehicle_T_sensor.inverse() * maps::Lift(from->inverse() * *to) * vehicle_T_sensor;
}

}  // namespace flat2d::localization::tools
