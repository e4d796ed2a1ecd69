// A synthetic world for the landmark SLAM tests: vertical walls (planes) outside a circular
// loop and poles (lines) inside and outside it, one of them on the world's z axis; a
// vehicle that drives the loop with a known truth; a dead reckoning with a scale error, a
// heading bias and noise; and per revolution the features of every landmark within range,
// in the sensor frame with noise, plus clutter and optionally corrupted features (wrong
// associations). Built from truth geometry with plain vector algebra, not from the
// library's transforms, so a sign error there does not cancel out here.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::localization::landmarks::testing {

struct Wall {  // the vertical rectangle over the segment a-b, z from 0 to height
  Eigen::Vector2d a, b;
  double height = 3.0;
  Eigen::Vector3d Center() const { return Eigen::Vector3d(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()), 0.5 * height); }
  Eigen::Vector3d Along() const { return Eigen::Vector3d(b.x() - a.x(), b.y() - a.y(), 0.0).normalized(); }
  double HalfLength() const { return 0.5 * (b - a).norm(); }
};

struct Pole {  // the vertical segment above `base`, `length` long
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  double length = 3.0;
};

struct World {
  std::vector<Wall> walls;
  std::vector<Pole> poles;
  int origin_pole = -1;  // the pole on the world's z axis
};

struct DriveSettings {
  double loop_radius_m = 8.0;
  double spacing_m = 0.3;
  int revolutions = 200;
  double range_m = 20.0;
  double odometry_scale_error = 0.03;      // dead reckoning travels 3 % too far
  double odometry_heading_bias = 6e-4;     // rad per revolution (~7 deg over 200)
  double odometry_heading_noise = 2e-3;    // rad per revolution
  double odometry_distance_noise_m = 3e-3;  // per revolution
  int clutter_per_revolution = 2;          // random planes and lines that are no landmark
  double corrupted_fraction = 0.0;         // of real features, moved and turned
  double corruption_offset_m = 0.5;
  double corruption_angle_rad = 5.0 * std::numbers::pi / 180.0;
  bool features = true;                    // false: odometry only
};

struct Revolution {
  Eigen::Isometry3d truth_world_T_vehicle = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d odometry_world_T_vehicle = Eigen::Isometry3d::Identity();
  maps::features3d::FeatureSet features;
};

struct Drive {
  World world;
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();
  std::vector<Revolution> revolutions;
  std::vector<int> wall_sightings;  // per wall, revolutions that saw it
  std::vector<int> pole_sightings;
};

// ~30 walls tangential to circles of radius 12-22 m (turned by up to 20 deg, so the vehicle
// on the 8 m loop always sees the same face), with two collinear pairs 5 m apart, and ~30
// poles inside and outside the loop, one at the world's origin.
World MakeLoopWorld(std::mt19937& rng);

// A long avenue bent into a circle of `radius` (68 m: the office drive's 428 m): walls
// every ~6 m on either side 5-12 m from the road, poles every ~4 m 2.5-8 m from it, so that
// a revolution sees some 25 landmarks within 20 m and each stays in view for ~40 m of road.
World MakeAvenueWorld(std::mt19937& rng, double radius);

// Drives `settings.revolutions` revolutions counterclockwise around the loop, starting at
// (R, 0) heading +y. `noise_rng` draws the odometry and feature noise and the clutter;
// `corruption_rng` only the corruption, so a corrupted drive differs from a clean one by
// the corruption alone.
Drive MakeDrive(const World& world, const DriveSettings& settings, std::mt19937& noise_rng,
                std::mt19937& corruption_rng);

// The office drive's size on the avenue of radius 68 m: 3600 revolutions over 428 m, ~25
// features each, a heading bias of ~20 deg over the drive. The world is drawn from `seed`,
// the noise from seed + 1 and the corruption from seed + 2.
Drive OfficeSizedDrive(unsigned seed);

}  // namespace flat2d::localization::landmarks::testing
