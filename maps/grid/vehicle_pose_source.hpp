// Where the vehicle was at a given time, in the odometry ("local") frame: what the grid
// builder asks to place each fan with the vehicle pose at its own time (motion compensation).
// maps/ cannot see localization/, so the daemon adapts its odometry pose history to this.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "hal/common/time.hpp"

namespace flat2d::maps {

class VehiclePoseSource {
 public:
  virtual ~VehiclePoseSource() = default;
  // local_T_vehicle at time t, or nullopt when t is outside what the source knows.
  virtual std::optional<Eigen::Isometry2d> PoseAt(TimeNs t) const = 0;
};

}  // namespace flat2d::maps
