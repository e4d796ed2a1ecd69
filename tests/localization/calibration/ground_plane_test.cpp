#include "localization/calibration/ground_plane.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "hal/common/angles.hpp"

namespace flat2d::localization::calibration {
namespace {


// vehicle_T_sensor's rotation, Z-Y-X.
Eigen::Matrix3d Rotation(double roll_deg, double pitch_deg, double yaw_deg) {
  return (Eigen::AngleAxisd(yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// A sensor `height` above flat ground, tilted: rings on the ground (1 cm noise), a wall
// 6 m ahead and a box on the ground, all in the sensor frame.
std::vector<Eigen::Vector3f> Scene(const Eigen::Matrix3d& vehicle_R_sensor, double height) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Eigen::Matrix3d sensor_R_vehicle = vehicle_R_sensor.transpose();
  const Eigen::Vector3d sensor_in_vehicle(0.0, 0.0, height);
  std::vector<Eigen::Vector3f> points;
  auto add = [&](const Eigen::Vector3d& vehicle_point) {
    points.push_back((sensor_R_vehicle * (vehicle_point - sensor_in_vehicle)).cast<float>());
  };
  for (int i = 0; i < 4000; ++i) {
    const double r = 2.5 + 20.0 * uniform(random), azimuth = 2.0 * std::numbers::pi * uniform(random);
    add({r * std::cos(azimuth), r * std::sin(azimuth), noise(random)});
  }
  for (int i = 0; i < 1500; ++i) add({6.0, -5.0 + 10.0 * uniform(random), 3.0 * uniform(random)});  // wall
  for (int i = 0; i < 150; ++i) add({-4.0 + uniform(random), 3.0 + uniform(random), 0.8});  // a box top, too small a plane
  return points;
}

TEST(GroundPlane, TiltedSensorGivesItsRollPitchAndHeight) {
  const Eigen::Matrix3d truth = Rotation(2.0, -3.0, 30.0);
  const std::vector<Eigen::Vector3f> points = Scene(truth, 1.6);
  // Guess 5 deg and 0.2 m off.
  const Eigen::Matrix3d guess = Rotation(7.0, -8.0, 35.0);
  const auto plane = FitGroundPlane(points, guess.transpose() * Eigen::Vector3d::UnitZ(), 1.8);
  ASSERT_TRUE(plane.has_value());
  EXPECT_NEAR(plane->height_m, 1.6, 0.005);
  EXPECT_GT(plane->inliers, 2500);  // of 4000: far returns where the guess tilts down are not candidates
  const Eigen::Vector2d roll_pitch = RollPitchOf(plane->normal);
  EXPECT_NEAR(roll_pitch.x() / kDegToRad, 2.0, 0.05);
  EXPECT_NEAR(roll_pitch.y() / kDegToRad, -3.0, 0.05);
}

TEST(GroundPlane, RollPitchOfInvertsTheMounting) {
  for (const auto& [roll, pitch, yaw] : {std::array{0.0, 0.0, 0.0}, {10.0, -20.0, 170.0}, {-45.0, 30.0, -90.0}}) {
    const Eigen::Vector2d rp = RollPitchOf(Rotation(roll, pitch, yaw).transpose() * Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(rp.x() / kDegToRad, roll, 1e-9);
    EXPECT_NEAR(rp.y() / kDegToRad, pitch, 1e-9);
  }
}

TEST(GroundPlane, NoGroundIsNone) {
  // Only the wall: no plane within the tilt limit.
  std::vector<Eigen::Vector3f> points = Scene(Eigen::Matrix3d::Identity(), 1.9);
  points.erase(points.begin(), points.begin() + 4000);
  points.resize(1500);
  EXPECT_FALSE(FitGroundPlane(points, Eigen::Vector3d::UnitZ(), 1.9).has_value());
  EXPECT_FALSE(FitGroundPlane({}, Eigen::Vector3d::UnitZ(), 1.9).has_value());
}

}  // namespace
}  // namespace flat2d::localization::calibration
