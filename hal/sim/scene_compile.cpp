#include "hal/sim/scene_compile.hpp"

#include <cmath>

#include "hal/sim/scene_footprint.hpp"

namespace flat2d::hal::sim::internal {
namespace {

std::uint8_t ReflectivityOr(std::uint32_t value, std::uint8_t fallback) {
  return value == 0 ? fallback : static_cast<std::uint8_t>(value);
}

Eigen::Vector2d ToEigen(const Vec2& v) { return {v.x(), v.y()}; }

// A box whose footprint runs from a to b with the given width, between two heights.
OrientedBox SegmentBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width,
                       double z_bottom, double z_top, std::uint8_t reflectivity) {
  const Eigen::Vector2d ab = b - a;
  const double length = ab.norm();
  OrientedBox box;
  box.center = 0.5 * (a + b);
  box.cos_yaw = ab.x() / length;
  box.sin_yaw = ab.y() / length;
  box.half_extent = Eigen::Vector3d(0.5 * length, 0.5 * width, 0.5 * (z_top - z_bottom));
  box.z_center = 0.5 * (z_bottom + z_top);
  box.reflectivity = reflectivity;
  return box;
}

// One box per segment of a polyline, lengthened by width / 2 at interior joints.
void AddPolylineBoxes(const google::protobuf::RepeatedPtrField<Vec2>& points, double width,
                      double z_bottom, double z_top, std::uint8_t reflectivity,
                      std::vector<OrientedBox>& boxes) {
  const int segments = points.size() - 1;
  for (int i = 0; i < segments; ++i) {
    Eigen::Vector2d a = ToEigen(points[i]);
    Eigen::Vector2d b = ToEigen(points[i + 1]);
    const Eigen::Vector2d along = (b - a).normalized() * (0.5 * width);
    if (i > 0) a -= along;
    if (i + 1 < segments) b += along;
    boxes.push_back(SegmentBox(a, b, width, z_bottom, z_top, reflectivity));
  }
}

void CompileSolids(const SceneDescription& d, CompiledStatics& out) {
  const double base = out.ground_height;
  for (const Box& b : d.boxes()) {
    OrientedBox box;
    box.center = ToEigen(b.center());
    box.cos_yaw = std::cos(b.yaw());
    box.sin_yaw = std::sin(b.yaw());
    box.half_extent = 0.5 * Eigen::Vector3d(b.length_m(), b.width_m(), b.height_m());
    box.z_center = base + b.bottom() + 0.5 * b.height_m();
    box.reflectivity = ReflectivityOr(b.reflectivity(), kDefaultBoxReflectivity);
    out.boxes.push_back(box);
  }
  for (const Wall& w : d.walls()) {
    AddPolylineBoxes(w.points(), w.thickness_m(), base + w.bottom(),
                     base + w.bottom() + w.height_m(),
                     ReflectivityOr(w.reflectivity(), kDefaultWallReflectivity), out.boxes);
  }
  for (const Curb& c : d.curbs()) {
    AddPolylineBoxes(c.points(), c.width_m(), base, base + c.height_m(),
                     ReflectivityOr(c.reflectivity(), kDefaultCurbReflectivity), out.boxes);
  }
  for (const Bar& b : d.bars()) {
    const double z = base + b.z();
    const double half = 0.5 * b.thickness_m();
    out.boxes.push_back(SegmentBox(ToEigen(b.a()), ToEigen(b.b()), b.thickness_m(), z - half,
                                   z + half,
                                   ReflectivityOr(b.reflectivity(), kDefaultBarReflectivity)));
  }
  for (const Cylinder& c : d.cylinders()) {
    const double bottom = base + c.bottom();
    out.cylinders.push_back({ToEigen(c.center()), c.radius_m(), bottom, bottom + c.height_m(),
                             ReflectivityOr(c.reflectivity(), kDefaultCylinderReflectivity)});
  }
  for (const ExtrudedPolygon& p : d.buildings()) {
    Prism prism;
    prism.first_vertex = static_cast<std::uint32_t>(out.prism_vertices.size());
    prism.vertex_count = static_cast<std::uint32_t>(p.vertices_size());
    prism.z_bottom = base + p.bottom();
    prism.z_top = prism.z_bottom + p.height_m();
    Eigen::AlignedBox2d bounds;
    for (const Vec2& v : p.vertices()) {
      out.prism_vertices.push_back(ToEigen(v));
      bounds.extend(ToEigen(v));
    }
    prism.min_xy = bounds.min();
    prism.max_xy = bounds.max();
    prism.reflectivity = ReflectivityOr(p.reflectivity(), kDefaultBuildingReflectivity);
    out.prisms.push_back(prism);
  }
  for (const Foliage& f : d.foliage()) {
    FoliageVolume volume;
    volume.volume = {ToEigen(f.center()), f.radius_m(), base + f.bottom(), base + f.top(),
                     ReflectivityOr(f.reflectivity(), kDefaultFoliageReflectivity)};
    volume.density_per_m = f.density_per_m();
    volume.index = static_cast<std::uint32_t>(out.foliage.size());
    out.foliage.push_back(volume);
  }
}

}  // namespace

CompiledStatics CompileScene(const SceneDescription& d) {
  CompiledStatics out;
  out.ground_height = d.ground().height();
  out.ground_reflectivity = ReflectivityOr(d.ground().reflectivity(), kDefaultGroundReflectivity);
  for (const Ramp& r : d.ground().ramps()) out.ramps.push_back(MakeRamp(r, out.ground_height));
  for (const LaneMarking& lane : d.lanes()) {
    const std::uint8_t reflectivity = ReflectivityOr(lane.reflectivity(), kDefaultLaneReflectivity);
    for (int i = 0; i + 1 < lane.points_size(); ++i) {
      out.lanes.push_back({ToEigen(lane.points(i)), ToEigen(lane.points(i + 1)),
                           0.5 * lane.width_m(), reflectivity});
    }
  }
  CompileSolids(d, out);
  for (const MovingObject& m : d.movers()) {
    const std::uint8_t reflectivity =
        m.has_box() ? ReflectivityOr(m.box().reflectivity(), kDefaultMovingBoxReflectivity)
                    : ReflectivityOr(m.cylinder().reflectivity(),
                                     kDefaultMovingCylinderReflectivity);
    out.movers.emplace_back(m, out.ground_height, reflectivity);
  }
  return out;
}

Eigen::AlignedBox2d SceneBounds(const CompiledStatics& s, const SceneDescription& d) {
  Eigen::AlignedBox2d bounds;
  for (const OrientedBox& b : s.boxes) bounds.extend(FootprintBounds(FootprintCorners(b)));
  for (const VerticalCylinder& c : s.cylinders) bounds.extend(FootprintBounds(c));
  for (const Eigen::Vector2d& v : s.prism_vertices) bounds.extend(v);
  for (const FoliageVolume& f : s.foliage) bounds.extend(FootprintBounds(f.volume));
  for (const RampSolid& r : s.ramps) bounds.extend(FootprintBounds(r.footprint));
  for (const LaneSegment& lane : s.lanes) bounds.extend(FootprintBounds(lane));
  for (const Drive& drive : d.drives()) {
    for (const Vec2& w : drive.waypoints()) bounds.extend(ToEigen(w));
  }
  return bounds;
}

}  // namespace flat2d::hal::sim::internal
