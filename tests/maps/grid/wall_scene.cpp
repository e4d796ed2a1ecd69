#include "tests/maps/grid/wall_scene.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include "hal/velodyne/laser_table.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::maps {

namespace {

// Where a ray from `origin` along `direction` first meets the ground or the wall; nullopt
// beyond 100 m.
std::optional<double> CastInScene(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  std::optional<double> best;
  if (direction.z() < 0.0) best = -origin.z() / direction.z();
  if (direction.x() > 0.0) {
    const double t = (kWallX - origin.x()) / direction.x();
    const Eigen::Vector3d hit = origin + t * direction;
    if (std::abs(hit.y()) < 8.0 && hit.z() >= 0.0 && hit.z() < 3.0 && (!best || t < *best)) best = t;
  }
  if (best && *best > 100.0) return std::nullopt;
  return best;
}

}  // namespace

std::vector<hal::velodyne::Fan> WallSceneFans(const StructureGridOptions& options, std::size_t count,
                                              const std::function<Eigen::Isometry2d(std::size_t)>& world_T_vehicle,
                                              std::size_t first_fan) {
  namespace velodyne = hal::velodyne;
  const velodyne::LaserTable table = velodyne::DefaultLaserTable(velodyne::Model::kVlp16);
  const Eigen::Isometry3d vehicle_T_sensor = VehicleFromSensor(options.mounting());
  std::vector<velodyne::Fan> fans(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Isometry3d world_T_sensor = Lift(world_T_vehicle(k)) * vehicle_T_sensor;
    const std::size_t index = (first_fan + k) % kWallSceneFansPerTurn;
    const double azimuth = 2.0 * std::numbers::pi * static_cast<double>(index) / kWallSceneFansPerTurn;
    velodyne::Fan& fan = fans[k];
    fan.stamp_ns = static_cast<TimeNs>(k) * 55'500;
    fan.azimuth_rad = static_cast<float>(azimuth);
    fan.num_lasers = static_cast<std::uint8_t>(table.num_lasers);
    for (int laser = 0; laser < table.num_lasers; ++laser) {
      const double elevation = table.lasers[static_cast<std::size_t>(laser)].elevation_rad;
      const Eigen::Vector3d direction(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                      std::sin(elevation));
      const auto t = CastInScene(world_T_sensor.translation(), world_T_sensor.linear() * direction);
      if (!t) continue;
      velodyne::LaserReturn& r = fan.returns[static_cast<std::size_t>(laser)];
      r.range_m = static_cast<float>(*t);
      r.xyz = (*t * direction).cast<float>();
      ++fan.num_points;
    }
  }
  return fans;
}

}  // namespace flat2d::maps
