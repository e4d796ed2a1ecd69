#include "maps/features3d/feature_extractor.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"
#include "hal/sim/scene.hpp"
#include "hal/sim/world_builder.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::maps::features3d {
namespace {

constexpr double kSensorHeightM = 1.9;

FeatureExtractionOptions Shipped() {
  auto options = LoadFeatureOptions(std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/features3d/features3d.textproto");
  EXPECT_TRUE(options.ok());
  return *options;
}

// A wall whose near face is x = 5.9, a street light at (3, 4) of radius 0.12 and a low box,
// on flat ground.
hal::sim::Scene StreetScene() {
  hal::sim::SceneDescription d;
  hal::sim::world::AddWall(d, {{6.0, -6.0}, {6.0, 6.0}}, 0.2, 3.0);
  hal::sim::world::AddCylinder(d, {3.0, 4.0}, 0.12, 6.0);
  hal::sim::world::AddBox(d, {-4.0, -3.0}, 0.3, 2.0, 1.0, 0.4);
  auto scene = hal::sim::Scene::Create(d);
  EXPECT_TRUE(scene.ok());
  return std::move(*scene);
}

// One ray per pixel of `projection` from a sensor 1.9 m above the origin, range noise
// sigma 1 cm (seeded): the points in the sensor frame.
std::vector<Eigen::Vector3f> Scan(const hal::sim::Scene& scene, const range3d::RangeProjection& projection,
                                  std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.01);
  const Eigen::Vector3d origin(0.0, 0.0, kSensorHeightM);
  std::vector<Eigen::Vector3f> points;
  for (int row = 0; row < projection.rows(); ++row) {
    for (int col = 0; col < projection.cols(); ++col) {
      const Eigen::Vector3d direction = projection.Unproject(row, col, 1.0F).cast<double>().normalized();
      const auto hit = scene.Cast(origin, direction, 100.0, 0.0);
      if (hit) points.push_back(((hit->range_m + noise(rng)) * direction).cast<float>());
    }
  }
  return points;
}

TEST(FeatureExtractor, FindsTheWallAndThePoleOfASimulatedRevolution) {
  const hal::sim::Scene scene = StreetScene();
  for (const auto sensor : {range3d::SensorModel::kVlp16, range3d::SensorModel::kHdl32e, range3d::SensorModel::kVlp32c}) {
    SCOPED_TRACE(std::string(range3d::SensorModelName(sensor)));
    const range3d::RangeProjection projection = range3d::LidarProjection(sensor, 2160);
    std::mt19937 rng(1);
    const auto points = Scan(scene, projection, rng);
    FeatureExtractor extractor(projection, Shipped());
    const FeatureSet& features = extractor.Extract(points, Eigen::Vector3f::UnitZ());
    // Every plane is a piece of the wall (the dense rows of a VLP-32C may leave its foot a
    // cluster of its own); the largest is the wall within 1 deg and 5 cm.
    ASSERT_GE(features.planes.size(), 1U);
    for (const PlaneFeature& p : features.planes) {
      EXPECT_LT(std::acos(std::min(1.0, -p.normal.x())) * kRadToDeg, 5.0);
      EXPECT_NEAR(p.d, 5.9, 0.1);
    }
    const PlaneFeature& wall = *std::max_element(features.planes.begin(), features.planes.end(),
                                                 [](const PlaneFeature& a, const PlaneFeature& b) { return a.points < b.points; });
    EXPECT_LT(std::acos(std::min(1.0, -wall.normal.x())) * kRadToDeg, 1.0);
    EXPECT_NEAR(wall.d, 5.9, 0.05);
    ASSERT_EQ(features.lines.size(), 1U);
    const LineFeature& pole = features.lines.front();
    EXPECT_LT(std::acos(std::min(1.0, pole.direction.z())) * kRadToDeg, 2.0);
    EXPECT_LT((pole.point.head<2>() - Eigen::Vector2d(3.0, 4.0)).norm(), 0.12 + 0.05);
    // The ground went at the non-vertical removal.
    EXPECT_LT(extractor.stats().vertical_points, extractor.stats().image_points / 2);
  }
}

// Without the removal every point of the image reaches normals and segmentation: the
// ground's too, which grows into clusters of its own, and the moving seed can creep from the
// ground up a wall through the smoothed normals of its foot (why the thesis removes it first).
TEST(FeatureExtractor, WithoutVerticalRemovalTheGroundIsSegmentedToo) {
  const hal::sim::Scene scene = StreetScene();
  const range3d::RangeProjection projection = range3d::LidarProjection(range3d::SensorModel::kHdl32e, 2160);
  std::mt19937 rng(2);
  const auto points = Scan(scene, projection, rng);
  FeatureExtractionOptions options = Shipped();
  FeatureExtractor with(projection, options);
  with.Extract(points, Eigen::Vector3f::UnitZ());
  options.mutable_vertical()->set_enabled(false);
  FeatureExtractor without(projection, options);
  without.Extract(points, Eigen::Vector3f::UnitZ());
  EXPECT_EQ(without.stats().vertical_points, without.stats().image_points);
  EXPECT_LT(with.stats().vertical_points, with.stats().image_points / 2);
  const auto clustered = [](const FeatureExtractor& e) { return e.clusters().points.size(); };
  std::printf("clustered points: %zu with the removal, %zu without\n", clustered(with), clustered(without));
  EXPECT_GT(clustered(without), clustered(with) + 1000);
}

// Points beyond max_range_m are left out; a second call gives the same features.
TEST(FeatureExtractor, RangeCutAndRepeatability) {
  const hal::sim::Scene scene = StreetScene();
  const range3d::RangeProjection projection = range3d::LidarProjection(range3d::SensorModel::kHdl32e, 2160);
  std::mt19937 rng(3);
  const auto points = Scan(scene, projection, rng);
  FeatureExtractionOptions options = Shipped();
  options.set_max_range_m(5.5);  // the pole (5 m away) stays, the wall (5.9 m) goes
  FeatureExtractor extractor(projection, options);
  const std::size_t lines = extractor.Extract(points, Eigen::Vector3f::UnitZ()).lines.size();
  const std::size_t planes = extractor.Extract(points, Eigen::Vector3f::UnitZ()).planes.size();
  EXPECT_EQ(lines, 1U);
  EXPECT_EQ(planes, 0U);
}

}  // namespace
}  // namespace flat2d::maps::features3d
