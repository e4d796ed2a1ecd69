// A small hand-built world for the LiDAR simulator's tests and benchmark: flat ground
// closed by a 60 x 60 m room of 20 m walls (so every ray meets a surface within 90 m), a
// box and a cylinder, and a drive with a corner inside it. It does not depend on the
// built-in worlds.
#pragma once

#include <utility>

#include "hal/sim/scene.pb.h"

namespace flat2d::testing {

inline void AddPoint(google::protobuf::RepeatedPtrField<hal::sim::Vec2>* points, double x, double y) {
  hal::sim::Vec2* p = points->Add();
  p->set_x(x);
  p->set_y(y);
}

inline hal::sim::SceneDescription LidarTestScene() {
  hal::sim::SceneDescription scene;
  scene.set_name("lidar-test");
  scene.mutable_ground()->set_height(0.0);
  scene.mutable_ground()->set_reflectivity(20);
  hal::sim::Wall* wall = scene.add_walls();
  for (const auto& [x, y] : {std::pair{-30.0, -30.0}, {30.0, -30.0}, {30.0, 30.0}, {-30.0, 30.0},
                             {-30.0, -30.0}}) {
    AddPoint(wall->mutable_points(), x, y);
  }
  wall->set_thickness_m(0.3);
  wall->set_height_m(20.0);
  wall->set_reflectivity(60);
  hal::sim::Box* box = scene.add_boxes();
  box->mutable_center()->set_x(8.0);
  box->mutable_center()->set_y(-5.0);
  box->set_yaw(0.3);
  box->set_length_m(4.0);
  box->set_width_m(2.0);
  box->set_height_m(1.5);
  box->set_reflectivity(100);
  hal::sim::Cylinder* cylinder = scene.add_cylinders();
  cylinder->mutable_center()->set_x(12.0);
  cylinder->mutable_center()->set_y(-14.0);
  cylinder->set_radius_m(0.3);
  cylinder->set_height_m(3.0);
  cylinder->set_reflectivity(150);
  return scene;
}

// Starts at rest at (-15, -10) heading east, turns left at (15, -10) towards (15, 10).
inline hal::sim::Drive LidarTestDrive() {
  hal::sim::Drive drive;
  drive.set_name("lidar-test");
  AddPoint(drive.mutable_waypoints(), -15.0, -10.0);
  AddPoint(drive.mutable_waypoints(), 15.0, -10.0);
  AddPoint(drive.mutable_waypoints(), 15.0, 10.0);
  drive.set_speed_mps(8.0);
  drive.set_corner_radius_m(6.0);
  drive.set_max_accel_mps2(3.0);
  return drive;
}

}  // namespace flat2d::testing
