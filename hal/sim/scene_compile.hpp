// Turns a validated SceneDescription into flat arrays of solids (internal to the Scene).
//
// Walls and curbs become one oriented box per polyline segment; at interior joints each
// segment is lengthened by half its thickness so corners close without a gap (the free
// ends stay where the description puts them, so door gaps keep their width). Bars become
// thin boxes. Heights are made absolute (base ground height + bottom). A reflectivity of 0
// becomes the kind's default (scene.proto documents the table).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/sim/scene.pb.h"
#include "hal/sim/scene_ground.hpp"
#include "hal/sim/scene_movers.hpp"
#include "hal/sim/scene_primitives.hpp"

namespace flat2d::hal::sim::internal {

// Default reflectivities (Velodyne calibrated reflectivity: 0-100 diffuse, 101-255
// retro-reflective), used where a description leaves reflectivity at 0.
inline constexpr std::uint8_t kDefaultGroundReflectivity = 12;     // asphalt
inline constexpr std::uint8_t kDefaultLaneReflectivity = 120;      // beaded road paint
inline constexpr std::uint8_t kDefaultBoxReflectivity = 40;
inline constexpr std::uint8_t kDefaultWallReflectivity = 50;
inline constexpr std::uint8_t kDefaultBuildingReflectivity = 45;
inline constexpr std::uint8_t kDefaultCylinderReflectivity = 60;   // poles, trunks
inline constexpr std::uint8_t kDefaultBarReflectivity = 70;        // metal rails
inline constexpr std::uint8_t kDefaultCurbReflectivity = 30;       // concrete
inline constexpr std::uint8_t kDefaultFoliageReflectivity = 25;
inline constexpr std::uint8_t kDefaultMovingBoxReflectivity = 55;  // car paint
inline constexpr std::uint8_t kDefaultMovingCylinderReflectivity = 20;  // clothing

struct CompiledStatics {
  double ground_height = 0.0;
  std::uint8_t ground_reflectivity = kDefaultGroundReflectivity;
  std::vector<OrientedBox> boxes;  // boxes, wall and curb segments, bars
  std::vector<VerticalCylinder> cylinders;
  std::vector<Prism> prisms;
  std::vector<Eigen::Vector2d> prism_vertices;
  std::vector<FoliageVolume> foliage;
  std::vector<RampSolid> ramps;
  std::vector<LaneSegment> lanes;
  std::vector<MoverTrack> movers;
};

// `description` must have passed ValidateScene.
CompiledStatics CompileScene(const SceneDescription& description);

// The XY box of every static solid, ramp, lane and drive waypoint (empty for an empty scene).
Eigen::AlignedBox2d SceneBounds(const CompiledStatics& statics,
                                const SceneDescription& description);

}  // namespace flat2d::hal::sim::internal
