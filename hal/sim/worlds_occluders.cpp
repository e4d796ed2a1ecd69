// The `occluders` world: ten boxes 0.1, 0.2, ... 1.0 m tall, evenly spaced in ascending
// order along a line that points at a wall (thesis 7.3.1, Fig. 7.6), so that from the
// front each box partly hides the taller ones behind it.
//
// The row runs along +x from x = 5 to x = 23 (2 m apart; each 0.5 m deep and 2 m wide)
// inside a walled 57 x 30 m room whose east wall stands behind the row. Drives look along
// the row from its short end (the figure's viewpoint), pass alongside it, and go round it.
#include "hal/sim/world_builder.hpp"

namespace flat2d::hal::sim::world {
namespace {

constexpr int kBoxes = 10;
constexpr double kFirstX = 5.0, kSpacing = 2.0, kDepth = 0.5, kWidth = 2.0, kStepHeight = 0.1;

void AddRoom(SceneDescription& scene) {
  AddWall(scene, {{-25, -15}, {32, -15}, {32, 15}, {-25, 15}, {-25, -15}}, 0.3, 3.0, kConcrete);
  for (const Point& p : {Point(-20, -10), Point(-20, 10), Point(0, 12), Point(15, -12)}) {
    AddCylinder(scene, p, 0.3, 3.0);
  }
}

void AddRow(SceneDescription& scene) {
  for (int i = 0; i < kBoxes; ++i) {
    AddBox(scene, {kFirstX + kSpacing * i, 0.0}, 0.0, kDepth, kWidth, kStepHeight * (i + 1),
           kPaintedWall);
  }
}

void AddOccludersDrives(SceneDescription& scene) {
  Drive* mapping = AddDrive(
      scene, "mapping",
      "Round the row at 1.5 m/s: east along its south side 7 m off, round its far end in "
      "front of the wall, west along its north side.",
      {{-18, -7}, {27.5, -7}, {27.5, 7}, {-18, 7}}, 1.5, 4.0);
  mapping->set_max_accel_mps2(0.5);

  Drive* towards = AddDrive(
      scene, "localize-1",
      "Towards the row along its axis at 1 m/s, stopping 6.7 m before the first box: the "
      "view of Fig. 7.6, where the shorter boxes hide the taller ones.",
      {{-20, 0}, {-2, 0}}, 1.0, 0.0);
  towards->set_max_accel_mps2(0.5);

  Drive* alongside = AddDrive(scene, "localize-2",
                              "East along the row's north side 10 m off, at 2 m/s.",
                              {{-18, 10}, {22, 10}}, 2.0, 0.0);
  alongside->set_world_time_offset_s(30.0);
}

}  // namespace

SceneDescription OccludersWorld() {
  SceneDescription scene;
  scene.set_name("occluders");
  scene.set_description(
      "Ten boxes 0.1 m to 1.0 m tall in ascending order, 2 m apart, in a line towards a wall "
      "(thesis 7.3.1, Fig. 7.6), in a walled 57 x 30 m room.");
  AddRoom(scene);
  AddRow(scene);
  AddOccludersDrives(scene);
  return scene;
}

}  // namespace flat2d::hal::sim::world
