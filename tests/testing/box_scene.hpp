// A ray-cast test scene for 3D registration: a room (the inside of a box) with box-shaped
// furniture, seen by a pinhole depth camera or a spinning LiDAR at a known pose.
//
// Exact depths (no noise unless asked), so registration tests can assert a recovered
// transform against the pose the images were rendered at.
#pragma once

#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "hal/cloud/point_cloud.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::testing {

struct AxisBox {
  Eigen::Vector3f min;
  Eigen::Vector3f max;
};

struct BoxScene {
  AxisBox room;                    // seen from inside
  std::vector<AxisBox> furniture;  // seen from outside

  // Distance along the unit ray from `origin` to the first surface, or 0 if none.
  float Cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) const;
};

// A 6 x 5 x 3 m room with a table, a cabinet and a pillar (world frame z up).
BoxScene OfficeRoom();

// The depth image a camera at world_T_camera (optical frame x right, y down, z forward)
// sees; Gaussian depth noise of sigma_m (0: exact) from `rng`.
hal::cloud::DepthImage RenderDepth(const BoxScene& scene, const maps::range3d::PinholeIntrinsics& intrinsics,
                                   const Eigen::Isometry3f& world_T_camera, float sigma_m, std::mt19937& rng);

// The points a LiDAR at world_T_sensor (x forward, z up) measures on `projection`'s rows
// and columns (one ray per pixel centre), in the sensor frame.
std::vector<Eigen::Vector3f> RenderLidar(const BoxScene& scene, const maps::range3d::RangeProjection& projection,
                                         const Eigen::Isometry3f& world_T_sensor);

// The range frame of a `sensor` revolution at world_T_sensor: RenderLidar on its laser rows
// and frames.lidar_columns columns, with the frames' statistics.
maps::range3d::RangeFrame RenderLidarFrame(const BoxScene& scene, maps::range3d::SensorModel sensor,
                                           const Eigen::Isometry3f& world_T_sensor,
                                           const maps::range3d::RangeFrameOptions& frames);

}  // namespace flat2d::testing
