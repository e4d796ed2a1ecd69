// The line and plane landmarks a world holds, for judging 3D feature extraction (thesis 8.1)
// against the truth: the vertical faces of its static solids (walls, boxes, buildings) as
// planes and its vertical cylinders (poles, trunks, pillars) as lines.
//
// Faces are the sides of the compiled solids (scene_compile.hpp), so a wall polyline gives
// two faces per segment, with the lengthening at joints the ray caster sees. Moving objects
// are not landmarks; MoversAt() says where they are so that an evaluation can set aside
// what is seen on them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim {

// A vertical rectangle: its footprint from a to b, outward unit normal (horizontal).
struct TruthFace {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  Eigen::Vector2d outward = Eigen::Vector2d::UnitX();
  double z_bottom = 0.0;
  double z_top = 0.0;
};

struct TruthPole {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double z_bottom = 0.0;
  double z_top = 0.0;
};

struct SceneLandmarks {
  std::vector<TruthFace> faces;
  std::vector<TruthPole> poles;
};

// Faces and poles at least `min_height_m` tall (lower ones, curbs and benches, are neither);
// `description` must be valid (Scene::Create checks).
SceneLandmarks StaticLandmarks(const SceneDescription& description, double min_height_m);

// Where each moving object is at `world_time_s`: its centre and the radius of a circle
// around its footprint.
struct MoverFootprint {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
};
std::vector<MoverFootprint> MoversAt(const SceneDescription& description, double world_time_s);

}  // namespace flat2d::hal::sim
