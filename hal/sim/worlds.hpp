// The built-in worlds of flat2d-sim, each a SceneDescription built procedurally (no
// randomness, so every build and run sees the same world):
//
//   office     one building floor of 75 x 85 m (thesis 7.3.3): a ring corridor and a
//              cross corridor 5 m wide, rooms with 1.5 m doors, furniture, pillars, a lobby.
//   campus     a 4-lane road loop of ~1.1 km with curbs, lane markings, buildings set
//              back from the road, poles, trees, fences, a car park, traffic and walkers.
//   ramps      10, 14.5 and 16 degree ramps side by side (thesis 7.3.1, Fig. 7.2), walls.
//   occluders  boxes 0.1 m to 1.0 m tall in ascending order before a wall (Fig. 7.6).
//
// Every world's drives[0] is its mapping drive, followed by at least two localization
// drives (other routes, starts, directions or world times), each keeping a 4.6 x 1.8 m
// vehicle at least 0.2 m clear of static structure.
#pragma once

#include <span>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim {

// The world called `name` (one of BuiltInWorldNames()); an error lists the names.
Result<SceneDescription> BuiltInWorld(std::string_view name);

std::span<const std::string_view> BuiltInWorldNames();

}  // namespace flat2d::hal::sim
