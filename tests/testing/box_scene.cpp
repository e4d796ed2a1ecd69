#include "tests/testing/box_scene.hpp"

#include <algorithm>
#include <limits>

namespace flat2d::testing {

namespace {

// Slab test: entry and exit distances of the ray through the box (entry > exit: miss).
std::pair<float, float> Slabs(const AxisBox& box, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  float entry = -std::numeric_limits<float>::infinity();
  float exit = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const float inverse = 1.0F / direction[axis];
    float t0 = (box.min[axis] - origin[axis]) * inverse;
    float t1 = (box.max[axis] - origin[axis]) * inverse;
    if (t0 > t1) std::swap(t0, t1);
    entry = std::max(entry, t0);
    exit = std::min(exit, t1);
  }
  return {entry, exit};
}

}  // namespace

float BoxScene::Cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) const {
  float nearest = Slabs(room, origin, direction).second;  // the inside wall the ray leaves by
  for (const AxisBox& box : furniture) {
    const auto [entry, exit] = Slabs(box, origin, direction);
    if (entry <= exit && entry > 0.0F) nearest = std::min(nearest, entry);
  }
  return std::isfinite(nearest) && nearest > 0.0F ? nearest : 0.0F;
}

BoxScene OfficeRoom() {
  BoxScene scene;
  scene.room = {{-3.0F, -2.5F, 0.0F}, {3.0F, 2.5F, 3.0F}};
  scene.furniture = {
      {{1.0F, -0.8F, 0.0F}, {2.2F, 0.4F, 0.75F}},    // table
      {{-2.9F, 1.2F, 0.0F}, {-2.2F, 2.4F, 1.9F}},   // cabinet
      {{0.3F, 1.3F, 0.0F}, {0.7F, 1.7F, 3.0F}},     // pillar
      {{-1.5F, -2.4F, 0.0F}, {-0.4F, -1.9F, 1.1F}},  // shelf
  };
  return scene;
}

hal::cloud::DepthImage RenderDepth(const BoxScene& scene, const maps::range3d::PinholeIntrinsics& intrinsics,
                                   const Eigen::Isometry3f& world_T_camera, float sigma_m, std::mt19937& rng) {
  hal::cloud::DepthImage image;
  image.width = intrinsics.cols;
  image.height = intrinsics.rows;
  image.depth_m.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height), 0.0F);
  std::normal_distribution<float> noise(0.0F, sigma_m);
  const Eigen::Vector3f origin = world_T_camera.translation();
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const Eigen::Vector3f ray((static_cast<float>(col) - intrinsics.cx) / intrinsics.fx,
                                (static_cast<float>(row) - intrinsics.cy) / intrinsics.fy, 1.0F);
      const float distance = scene.Cast(origin, (world_T_camera.linear() * ray).normalized());
      if (distance <= 0.0F) continue;
      const float depth = distance / ray.norm();  // z of the hit in the camera frame
      image.depth_m[static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(col)] =
          sigma_m > 0.0F ? depth + noise(rng) : depth;
    }
  }
  return image;
}

std::vector<Eigen::Vector3f> RenderLidar(const BoxScene& scene, const maps::range3d::RangeProjection& projection,
                                         const Eigen::Isometry3f& world_T_sensor) {
  std::vector<Eigen::Vector3f> points;
  for (int row = 0; row < projection.rows(); ++row) {
    for (int col = 0; col < projection.cols(); ++col) {
      const Eigen::Vector3f direction = projection.Unproject(row, col, 1.0F);
      const float distance = scene.Cast(world_T_sensor.translation(), world_T_sensor.linear() * direction);
      if (distance > 0.0F) points.push_back(direction * distance);
    }
  }
  return points;
}

maps::range3d::RangeFrame RenderLidarFrame(const BoxScene& scene, maps::range3d::SensorModel sensor,
                                           const Eigen::Isometry3f& world_T_sensor,
                                           const maps::range3d::RangeFrameOptions& frames) {
  hal::cloud::PointCloud cloud;
  cloud.points = RenderLidar(scene, maps::range3d::LidarProjection(sensor, frames.lidar_columns), world_T_sensor);
  return maps::range3d::FrameFromCloud(cloud, sensor, frames);
}

}  // namespace flat2d::testing
