#include "localization/evaluation/feature_accuracy.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace flat2d::localization::evaluation {
namespace {

// A wall face x = 5 (y in [-3, 3], facing -x) 3 m tall, a pole at (3, 4), a door-jamb edge,
// seen by a sensor 1.9 m above the origin, yawed 30 deg so that sensor and world differ.
struct Fixture {
  hal::sim::SceneLandmarks truth;
  Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3f> points;  // sensor frame: 200 on the wall, 40 on the pole

  Fixture() {
    truth.faces.push_back({{5.0, 3.0}, {5.0, -3.0}, {-1.0, 0.0}, 0.0, 3.0});
    truth.faces.push_back({{-4.0, 2.0}, {-4.0, 2.15}, {1.0, 0.0}, 0.0, 3.0});  // 0.15 m wide: an edge
    truth.poles.push_back({{3.0, 4.0}, 0.12, 0.0, 6.0});
    world_T_sensor.translate(Eigen::Vector3d(0.0, 0.0, 1.9)).rotate(Eigen::AngleAxisd(0.5236, Eigen::Vector3d::UnitZ()));
    const Eigen::Isometry3d sensor_T_world = world_T_sensor.inverse();
    for (int k = 0; k < 200; ++k) {
      points.push_back((sensor_T_world * Eigen::Vector3d(5.0, -2.5 + 0.025 * k, 0.5 + 0.01 * k)).cast<float>());
    }
    for (int k = 0; k < 40; ++k) {
      const double a = std::atan2(-4.0, -3.0) + 0.02 * (k % 10 - 5);
      points.push_back((sensor_T_world * Eigen::Vector3d(3.0 + 0.12 * std::cos(a), 4.0 + 0.12 * std::sin(a), 0.2 + 0.1 * k))
                           .cast<float>());
    }
  }

  maps::features3d::PlaneFeature Wall(double tilt_rad, double shift_m) const {
    maps::features3d::PlaneFeature plane;
    const Eigen::Vector3d world_normal = Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(-1, 0, 0);
    const Eigen::Vector3d world_centroid(5.0 + shift_m, 0.0, 1.5);
    plane.normal = world_T_sensor.linear().transpose() * world_normal;
    plane.centroid = world_T_sensor.inverse() * world_centroid;
    plane.d = -plane.normal.dot(plane.centroid);
    return plane;
  }
  maps::features3d::LineFeature Line(const Eigen::Vector3d& world_point) const {
    maps::features3d::LineFeature line;
    line.point = world_T_sensor.inverse() * world_point;
    line.direction = world_T_sensor.linear().transpose() * Eigen::Vector3d::UnitZ();
    return line;
  }
};

TEST(FeatureAccuracy, ExactFeaturesMatchWithZeroError) {
  const Fixture f;
  maps::features3d::FeatureSet features;
  features.planes.push_back(f.Wall(0.0, 0.0));
  features.lines.push_back(f.Line({3.0 - 0.08, 4.0 - 0.0, 1.0}));
  const RevolutionAccuracy a = EvaluateFeatures(features, f.points, f.world_T_sensor, f.truth, {}, {});
  EXPECT_EQ(a.faces_in_view, std::vector<int>{0});  // the edge is no plane to find
  EXPECT_EQ(a.poles_in_view, std::vector<int>{0});
  EXPECT_EQ(a.planes_matched, 1);
  EXPECT_EQ(a.faces_found, std::vector<int>{0});
  ASSERT_EQ(a.normal_error_deg.size(), 1U);
  EXPECT_NEAR(a.normal_error_deg[0], 0.0, 1e-6);
  EXPECT_NEAR(a.offset_error_m[0], 0.0, 1e-9);
  EXPECT_EQ(a.lines_matched, 1);
  EXPECT_NEAR(a.axis_distance_m[0], 0.08, 1e-9);
  EXPECT_NEAR(a.direction_error_deg[0], 0.0, 1e-6);
}

TEST(FeatureAccuracy, ErrorsAreMeasuredAndFarOnesRejected) {
  const Fixture f;
  maps::features3d::FeatureSet features;
  features.planes.push_back(f.Wall(3.0 * 3.14159265 / 180.0, 0.04));   // 3 deg, 4 cm: matched with those errors
  features.planes.push_back(f.Wall(20.0 * 3.14159265 / 180.0, 0.0));   // beyond the 10 deg gate
  features.lines.push_back(f.Line({-4.0, 2.075, 1.0}));                 // on the edge
  features.lines.push_back(f.Line({0.0, -6.0, 1.0}));                   // nothing there
  const RevolutionAccuracy a = EvaluateFeatures(features, f.points, f.world_T_sensor, f.truth, {}, {});
  EXPECT_EQ(a.planes, 2);
  EXPECT_EQ(a.planes_matched, 1);
  ASSERT_EQ(a.normal_error_deg.size(), 1U);
  EXPECT_NEAR(a.normal_error_deg[0], 3.0, 1e-3);
  EXPECT_GT(a.offset_error_m[0], 0.03);
  EXPECT_EQ(a.lines, 2);
  EXPECT_EQ(a.lines_matched, 1);
  EXPECT_EQ(a.lines_on_edges, 1);
  EXPECT_TRUE(a.poles_found.empty());
}

TEST(FeatureAccuracy, FewPointsAreNotInViewAndMoversAreSetAside) {
  Fixture f;
  f.points.resize(10);  // a glimpse of the wall only
  maps::features3d::FeatureSet features;
  features.lines.push_back(f.Line({0.0, -6.0, 1.0}));
  const std::vector<hal::sim::MoverFootprint> movers{{{0.0, -6.5}, 2.0}};
  const RevolutionAccuracy a = EvaluateFeatures(features, f.points, f.world_T_sensor, f.truth, movers, {});
  EXPECT_TRUE(a.faces_in_view.empty());
  EXPECT_TRUE(a.poles_in_view.empty());
  EXPECT_EQ(a.lines, 0);
  EXPECT_EQ(a.on_movers, 1);
}

}  // namespace
}  // namespace flat2d::localization::evaluation
