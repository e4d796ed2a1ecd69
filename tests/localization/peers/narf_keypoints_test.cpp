// The NARF peer's detector (narf_keypoints.hpp) on a synthetic HDL-32E-like revolution: 32
// rings from -30.67 to +10.67 deg, one firing every 0.2 deg, cast against a ground plane
// 1.7 m below the sensor and a 1.5 m box 8 m ahead. Key-points must come back in the
// sensor frame as measured points (not the range image's pixel centres), and some at the
// box, whose corners and edges are the scene's only structure.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "localization/peers/narf_keypoints.hpp"

namespace flat2d::localization::peers {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
const Eigen::Vector3d kBoxMin(7.25, -0.75, -1.7), kBoxMax(8.75, 0.75, -0.2);

// Range along unit `ray` to the axis-aligned box (slab method), or infinity.
double BoxRange(const Eigen::Vector3d& ray) {
  double near = 0.0, far = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ray(k)) < 1e-12) {
      if (0.0 < kBoxMin(k) || 0.0 > kBoxMax(k)) return far;
      continue;
    }
    const double t0 = kBoxMin(k) / ray(k), t1 = kBoxMax(k) / ray(k);
    near = std::max(near, std::min(t0, t1));
    far = std::min(far, std::max(t0, t1));
  }
  return near <= far ? near : std::numeric_limits<double>::infinity();
}

hal::cloud::PointCloud SyntheticRevolution() {
  hal::cloud::PointCloud cloud;
  for (int ring = 0; ring < 32; ++ring) {
    const double elevation = (-30.67 + 1.33 * ring) * kDegree;
    for (int column = 0; column < 1800; ++column) {
      const double azimuth = 0.2 * column * kDegree;
      const Eigen::Vector3d ray(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
      double range = BoxRange(ray);
      if (ray.z() < 0.0) range = std::min(range, -1.7 / ray.z());
      if (range > 70.0) continue;  // no return
      cloud.points.push_back((range * ray).cast<float>());
    }
  }
  return cloud;
}

TEST(NarfKeypoints, FindTheBoxOnTheGroundInTheSensorFrame) {
  const hal::cloud::PointCloud cloud = SyntheticRevolution();
  const NarfKeypoints keypoints = DetectNarfKeypoints(cloud, NarfOptions{});
  std::printf("%zu points, image %d x %d, %zu key-points\n", cloud.points.size(), keypoints.image_width,
              keypoints.image_height, keypoints.points.size());
  EXPECT_EQ(keypoints.image_width, 1800);
  ASSERT_FALSE(keypoints.points.empty());
  int at_box = 0;
  for (const Eigen::Vector3d& k : keypoints.points) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3f& p : cloud.points) nearest = std::min(nearest, (p.cast<double>() - k).norm());
    EXPECT_LE(nearest, 1e-4) << "a key-point that is no measured point: " << k.transpose();
    const Eigen::Vector3d outside = (k - k.cwiseMax(kBoxMin).cwiseMin(kBoxMax));
    if (outside.norm() <= 0.3) ++at_box;
  }
  EXPECT_GE(at_box, 1);
}

TEST(NarfKeypoints, EmptyCloudHasNone) {
  const NarfKeypoints keypoints = DetectNarfKeypoints(hal::cloud::PointCloud{}, NarfOptions{});
  EXPECT_TRUE(keypoints.points.empty());
}

}  // namespace
}  // namespace flat2d::localization::peers
