// Helpers for the Scene tests: descriptions from protobuf text and short cast calls.
#pragma once

#include <string>

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include "hal/sim/scene.hpp"

namespace flat2d::hal::sim::testing {

inline SceneDescription ParseScene(const std::string& text) {
  SceneDescription description;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &description)) << text;
  return description;
}

inline Scene MakeScene(const std::string& text) {
  Result<Scene> scene = Scene::Create(ParseScene(text));
  if (!scene.ok()) ADD_FAILURE() << scene.error().message;
  if (!scene.ok()) return std::move(Scene::Create(SceneDescription()).value());
  return std::move(scene).value();
}

// Casts from `origin` towards `towards` (normalised here) with a 200 m range.
inline std::optional<SurfaceHit> CastTowards(const Scene& scene, const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& towards, double time_s = 0.0,
                                             double max_range_m = 200.0) {
  return scene.Cast(origin, towards.normalized(), max_range_m, time_s);
}

}  // namespace flat2d::hal::sim::testing
