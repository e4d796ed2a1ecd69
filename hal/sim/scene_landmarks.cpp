#include "hal/sim/scene_landmarks.hpp"

#include <cmath>

#include "hal/sim/scene_compile.hpp"

namespace flat2d::hal::sim {
namespace {

// The four sides of an oriented box, each with its outward normal.
void AddBoxFaces(const internal::OrientedBox& box, std::vector<TruthFace>& faces) {
  const Eigen::Vector2d along(box.cos_yaw, box.sin_yaw), across(-box.sin_yaw, box.cos_yaw);
  const Eigen::Vector2d ha = along * box.half_extent.x(), hc = across * box.half_extent.y();
  const Eigen::Vector2d corners[4] = {box.center - ha - hc, box.center + ha - hc, box.center + ha + hc,
                                      box.center - ha + hc};  // counter-clockwise
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = corners[k];
    const Eigen::Vector2d& b = corners[(k + 1) % 4];
    const Eigen::Vector2d edge = (b - a).normalized();
    faces.push_back({a, b, Eigen::Vector2d(edge.y(), -edge.x()), box.z_bottom(), box.z_top()});
  }
}

// The sides of a counter-clockwise polygon extruded between two heights.
void AddPrismFaces(const internal::Prism& prism, const std::vector<Eigen::Vector2d>& vertices,
                   std::vector<TruthFace>& faces) {
  for (std::uint32_t k = 0; k < prism.vertex_count; ++k) {
    const Eigen::Vector2d& a = vertices[prism.first_vertex + k];
    const Eigen::Vector2d& b = vertices[prism.first_vertex + (k + 1) % prism.vertex_count];
    const Eigen::Vector2d edge = (b - a).normalized();
    faces.push_back({a, b, Eigen::Vector2d(edge.y(), -edge.x()), prism.z_bottom, prism.z_top});
  }
}

}  // namespace

SceneLandmarks StaticLandmarks(const SceneDescription& description, double min_height_m) {
  const internal::CompiledStatics statics = internal::CompileScene(description);
  SceneLandmarks landmarks;
  for (const internal::OrientedBox& box : statics.boxes) {
    if (2.0 * box.half_extent.z() >= min_height_m) AddBoxFaces(box, landmarks.faces);
  }
  for (const internal::Prism& prism : statics.prisms) {
    if (prism.z_top - prism.z_bottom >= min_height_m) AddPrismFaces(prism, statics.prism_vertices, landmarks.faces);
  }
  for (const internal::VerticalCylinder& c : statics.cylinders) {
    if (c.z_top - c.z_bottom >= min_height_m) landmarks.poles.push_back({c.center, c.radius, c.z_bottom, c.z_top});
  }
  return landmarks;
}

std::vector<MoverFootprint> MoversAt(const SceneDescription& description, double world_time_s) {
  const internal::CompiledStatics statics = internal::CompileScene(description);
  std::vector<MoverFootprint> movers;
  for (int i = 0; i < description.movers_size(); ++i) {
    const MovingObject& m = description.movers(i);
    const double radius = m.has_box() ? 0.5 * std::hypot(m.box().length_m(), m.box().width_m()) : m.cylinder().radius_m();
    movers.push_back({statics.movers[static_cast<std::size_t>(i)].PoseAt(world_time_s).position, radius});
  }
  return movers;
}

}  // namespace flat2d::hal::sim
