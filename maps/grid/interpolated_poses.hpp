// A VehiclePoseSource over a recorded trajectory (a truth.tum, an estimate): poses at any time
// between the first and the last, interpolated linearly in position and along the shorter
// arc in heading. 3D poses are flattened to (x, y, yaw), yaw from the body's x axis.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "hal/common/time.hpp"
#include "maps/grid/vehicle_pose_source.hpp"

namespace flat2d::maps {

struct StampedPose2d {
  TimeNs time_ns = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double yaw = 0.0;
};

// (x, y, yaw) of a 3D pose: position and the heading of its x axis projected on the plane.
StampedPose2d Flatten(TimeNs time_ns, const Eigen::Isometry3d& world_T_body);

// The 3D pose of a planar one: on the ground plane (z, roll and pitch zero).
Eigen::Isometry3d Lift(const Eigen::Isometry2d& pose);

class InterpolatedPoses : public VehiclePoseSource {
 public:
  // poses in increasing time order.
  explicit InterpolatedPoses(std::vector<StampedPose2d> poses);

  std::optional<Eigen::Isometry2d> PoseAt(TimeNs t) const override;
  const std::vector<StampedPose2d>& poses() const { return poses_; }

 private:
  std::vector<StampedPose2d> poses_;
};

}  // namespace flat2d::maps
