#include "hal/sim/scene_ground.hpp"

#include <algorithm>
#include <cmath>

#include "hal/common/angles.hpp"

namespace flat2d::hal::sim::internal {
namespace {

HalfSpace Face(const Eigen::Vector3d& normal, double offset) {
  const double norm = normal.norm();
  return HalfSpace{normal / norm, offset / norm};
}

void AddFace(ConvexSolid& solid, const HalfSpace& face) {
  solid.faces[static_cast<std::size_t>(solid.face_count++)] = face;
}

// The ramp's cross-section in the (u, z) plane, counter-clockwise.
std::array<Eigen::Vector2d, 4> CrossSection(const RampSolid& r) {
  const double top = r.base + r.rise;
  return {Eigen::Vector2d(0.0, r.base), Eigen::Vector2d(r.length, r.base),
          Eigen::Vector2d(r.run + r.plateau, top), Eigen::Vector2d(r.run, top)};
}

}  // namespace

RampSolid MakeRamp(const Ramp& ramp, double base) {
  RampSolid r;
  r.start = Eigen::Vector2d(ramp.start().x(), ramp.start().y());
  r.cos_heading = std::cos(ramp.heading());
  r.sin_heading = std::sin(ramp.heading());
  r.tan_slope = std::tan(ramp.slope_deg() * kDegToRad);
  r.run = ramp.run_m();
  r.plateau = ramp.plateau_m();
  r.descend = ramp.descend();
  r.length = (r.descend ? 2.0 * r.run : r.run) + r.plateau;
  r.half_width = 0.5 * ramp.width_m();
  r.base = base;
  r.rise = r.run * r.tan_slope;

  const Eigen::Vector3d eu(r.cos_heading, r.sin_heading, 0.0);
  const Eigen::Vector3d ev(-r.sin_heading, r.cos_heading, 0.0);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const double u0 = eu.head<2>().dot(r.start);  // u = eu . x - u0
  const double v0 = ev.head<2>().dot(r.start);
  ConvexSolid& s = r.solid;
  AddFace(s, Face(-up, -base));
  AddFace(s, Face(up - r.tan_slope * eu, base - r.tan_slope * u0));  // rise
  AddFace(s, Face(up, base + r.rise));                                 // plateau
  if (r.descend) {
    AddFace(s, Face(up + r.tan_slope * eu, base + r.tan_slope * (r.length + u0)));  // fall
  }
  AddFace(s, Face(eu, u0 + r.length));  // the drop-off face, or the far end
  AddFace(s, Face(-eu, -u0));
  AddFace(s, Face(ev, v0 + r.half_width));
  AddFace(s, Face(-ev, -v0 + r.half_width));

  const Eigen::Vector2d along = eu.head<2>();
  const Eigen::Vector2d across = ev.head<2>() * r.half_width;
  r.footprint = {r.start - across, r.start + r.length * along - across,
                 r.start + r.length * along + across, r.start + across};
  return r;
}

Eigen::Vector2d RampSolid::ToLocal(double x, double y) const {
  const double dx = x - start.x();
  const double dy = y - start.y();
  return {cos_heading * dx + sin_heading * dy, -sin_heading * dx + cos_heading * dy};
}

std::optional<double> RampSolid::HeightAt(double x, double y) const {
  const Eigen::Vector2d uv = ToLocal(x, y);
  const double u = uv.x();
  if (u < 0.0 || u > length || std::abs(uv.y()) > half_width) return std::nullopt;
  if (u <= run) return base + u * tan_slope;
  if (u <= run + plateau || !descend) return base + rise;
  return base + (length - u) * tan_slope;
}

Eigen::Vector3d RampSolid::NormalAt(double x, double y) const {
  const double u = ToLocal(x, y).x();
  double gradient = 0.0;  // dz/du of the piece under (x, y)
  if (u <= run) {
    gradient = tan_slope;
  } else if (u > run + plateau && descend) {
    gradient = -tan_slope;
  }
  return Eigen::Vector3d(-gradient * cos_heading, -gradient * sin_heading, 1.0).normalized();
}

double RampSolid::DistanceToSurface(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d uv = ToLocal(p.x(), p.y());
  const auto section = CrossSection(*this);
  const double in_plane =
      SignedDistanceToPolygon(section.data(), 4, Eigen::Vector2d(uv.x(), p.z()));
  return ExtrudedSurfaceDistance(in_plane, std::abs(uv.y()) - half_width);
}

bool LaneSegment::Covers(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).squaredNorm() <= half_width * half_width;
}

}  // namespace flat2d::hal::sim::internal
