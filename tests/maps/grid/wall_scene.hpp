// A synthetic VLP-16 drive for structure-grid tests: flat ground (z = 0) and a 3 m wall
// across x = kWallX for |y| < 8 m, fired from a vehicle whose pose per fan the test chooses.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "hal/velodyne/fan.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::maps {

inline constexpr double kWallX = 10.0;
inline constexpr std::size_t kWallSceneFansPerTurn = 1800;  // 0.2 deg apart

// Fans k = 0 .. count-1 at azimuth (first_azimuth + k 0.2 deg) mod 360, stamped k x 55.5 us,
// fired with the vehicle at world_T_vehicle(k) (the sensor mounted as options say).
std::vector<hal::velodyne::Fan> WallSceneFans(const StructureGridOptions& options, std::size_t count,
                                              const std::function<Eigen::Isometry2d(std::size_t)>& world_T_vehicle,
                                              std::size_t first_fan = 0);

inline std::vector<hal::velodyne::Fan> WallSceneRevolution(
    const StructureGridOptions& options, const std::function<Eigen::Isometry2d(std::size_t)>& world_T_vehicle) {
  return WallSceneFans(options, kWallSceneFansPerTurn, world_T_vehicle);
}

}  // namespace flat2d::maps
