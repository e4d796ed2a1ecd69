// The `ramps` world: a 16, a 14.5 and a 10 degree ramp side by side, left to right as in
// thesis Fig. 7.2 (7.3.1), near the 15 degree hazard threshold, on flat ground inside a
// walled yard that gives scan matching something to hold on to.
//
// Each ramp points north (+y) from y = 0: it rises over 6 m, stays level for 5 m and falls
// over 6 m, 3.5 m wide. Drives pass south of them looking at their low ends, north of them,
// and one drives over the 10 degree ramp (its plateau is longer than the wheelbase, so the
// vehicle sits level on top before it goes down).
#include <cmath>
#include <numbers>

#include "hal/sim/world_builder.hpp"

namespace flat2d::hal::sim::world {
namespace {

constexpr double kRampRun = 6.0, kRampPlateau = 5.0, kRampWidth = 3.5;
struct RampSpec {
  double x;
  double slope_deg;
};
constexpr RampSpec kRamps[] = {{0.0, 16.0}, {8.0, 14.5}, {16.0, 10.0}};

void AddRamps(SceneDescription& scene) {
  for (const RampSpec& spec : kRamps) {
    Ramp* ramp = scene.mutable_ground()->add_ramps();
    SetPoint(ramp->mutable_start(), {spec.x, 0.0});
    ramp->set_heading(std::numbers::pi / 2);
    ramp->set_run_m(kRampRun);
    ramp->set_width_m(kRampWidth);
    ramp->set_slope_deg(spec.slope_deg);
    ramp->set_plateau_m(kRampPlateau);
    ramp->set_descend(true);
  }
}

void AddYard(SceneDescription& scene) {
  // Walls round [-20, 40] x [-40, 60], a gate in the north wall, a shed and some crates.
  AddWall(scene, {{-20, 60}, {-20, -40}, {40, -40}, {40, 60}, {22, 60}}, 0.3, 3.0, kConcrete);
  AddWall(scene, {{2, 60}, {-20, 60}}, 0.3, 3.0, kConcrete);
  AddBuilding(scene, Rectangle(-19, 28, -15, 38), 3.5);           // shed
  AddBox(scene, {24, 33}, 0.3, 1.2, 1.2, 1.2);                    // crates
  AddBox(scene, {26, 36}, -0.2, 1.2, 1.2, 2.4);
  AddCylinder(scene, {-5, -25}, 0.15, 4.0, kMetal);               // lamp posts
  AddCylinder(scene, {25, -25}, 0.15, 4.0, kMetal);
  AddCylinder(scene, {25, 45}, 0.15, 4.0, kMetal);
  AddBox(scene, {8, 45}, 0.0, 6.0, 0.6, 1.0, kConcrete);          // a low barrier
}

void AddRampsDrives(SceneDescription& scene) {
  Drive* mapping = AddDrive(
      scene, "mapping",
      "Anticlockwise round the ramps inside the yard at 3 m/s, starting and ending in the "
      "south-west.",
      {{-12, -30}, {32, -30}, {32, 52}, {-12, 52}, {-12, -20}}, 3.0, 6.0);
  mapping->set_max_accel_mps2(0.8);

  AddDrive(scene, "localize-1",
           "East along y = -10 at 2 m/s, looking at the ramps' low ends from 10 m (the "
           "viewpoint of Fig. 7.2).",
           {{-14, -10}, {34, -10}}, 2.0, 0.0);

  Drive* over = AddDrive(scene, "over-10deg",
                         "North over the 10 degree ramp at 2 m/s: up 6 m, level 5 m, down 6 m.",
                         {{16, -30}, {16, 52}}, 2.0, 0.0);
  over->set_world_time_offset_s(60.0);

  Drive* north = AddDrive(scene, "localize-2",
                          "West along y = 26, behind the ramps' far ends, at 2.5 m/s.",
                          {{34, 26}, {-14, 26}}, 2.5, 0.0);
  north->set_world_time_offset_s(120.0);
}

}  // namespace

SceneDescription RampsWorld() {
  SceneDescription scene;
  scene.set_name("ramps");
  scene.set_description(
      "Ramps of 16, 14.5 and 10 degrees side by side (thesis 7.3.1, Fig. 7.2), each rising "
      "over 6 m, level for 5 m and falling over 6 m, in a walled 60 x 100 m yard.");
  AddRamps(scene);
  AddYard(scene);
  AddRampsDrives(scene);
  return scene;
}

}  // namespace flat2d::hal::sim::world
