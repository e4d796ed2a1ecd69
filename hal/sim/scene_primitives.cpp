#include "hal/sim/scene_primitives.hpp"

#include <algorithm>
#include <bit>

namespace flat2d::hal::sim::internal {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Quick reject: does the ray meet the prism's bounding box before t_max?
bool MeetsBounds(const Prism& prism, const Ray& ray, double t_max) {
  double t_near = 0.0;
  double t_far = t_max;
  bool entered = false;
  bool left = false;
  return ClipSlab(ray.origin.x(), ray.direction.x(), prism.min_xy.x(), prism.max_xy.x(), t_near,
                  t_far, entered, left) &&
         ClipSlab(ray.origin.y(), ray.direction.y(), prism.min_xy.y(), prism.max_xy.y(), t_near,
                  t_far, entered, left) &&
         ClipSlab(ray.origin.z(), ray.direction.z(), prism.z_bottom, prism.z_top, t_near, t_far,
                  entered, left);
}

// SplitMix64 finaliser (Steele, Lea and Flood 2014): a cheap, well-mixed 64-bit hash step.
std::uint64_t Mix(std::uint64_t state, std::uint64_t value) {
  std::uint64_t z = state + value + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t Bits(double value) { return std::bit_cast<std::uint64_t>(value + 0.0); }

// A uniform draw in (0, 1) that depends only on the ray, the time and the volume.
double RayUniform(const Ray& ray, double world_time_s, std::uint32_t salt) {
  std::uint64_t h = Mix(0x5EED5EED5EED5EEDULL, salt);
  for (int i = 0; i < 3; ++i) h = Mix(h, Bits(ray.origin[i]));
  for (int i = 0; i < 3; ++i) h = Mix(h, Bits(ray.direction[i]));
  h = Mix(h, Bits(world_time_s));
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

double DistanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

}  // namespace

std::optional<PrimitiveHit> IntersectPrism(const Prism& prism, const Eigen::Vector2d* vertices,
                                           const Ray& ray, double t_max) {
  if (!MeetsBounds(prism, ray, t_max)) return std::nullopt;
  const Eigen::Vector2d* v = vertices + prism.first_vertex;
  const std::uint32_t n = prism.vertex_count;
  const Eigen::Vector2d o = ray.origin.head<2>();
  const Eigen::Vector2d d = ray.direction.head<2>();
  std::optional<PrimitiveHit> best;
  double best_t = t_max;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d edge = v[(i + 1) % n] - a;
    const double denom = Cross(d, edge);
    if (std::abs(denom) < kParallelEpsilon) continue;  // parallel: grazes at most an edge
    const Eigen::Vector2d ao = a - o;
    const double t = Cross(ao, edge) / denom;
    const double s = Cross(ao, d) / denom;
    if (t < 0.0 || t >= best_t || s < 0.0 || s > 1.0) continue;
    const double z = ray.origin.z() + t * ray.direction.z();
    if (z < prism.z_bottom || z > prism.z_top) continue;
    const Eigen::Vector3d outward = Eigen::Vector3d(edge.y(), -edge.x(), 0.0).normalized();
    best_t = t;
    best = PrimitiveHit{t, FacingOrigin(outward, ray.direction)};
  }
  if (std::abs(ray.direction.z()) >= kParallelEpsilon) {
    for (const double z_cap : {prism.z_bottom, prism.z_top}) {
      const double t = (z_cap - ray.origin.z()) / ray.direction.z();
      if (t < 0.0 || t >= best_t) continue;
      const Eigen::Vector2d p = o + t * d;
      if (!InsidePolygon(v, n, p.x(), p.y())) continue;
      best_t = t;
      best = PrimitiveHit{t, FacingOrigin(Eigen::Vector3d::UnitZ(), ray.direction)};
    }
  }
  return best;
}

std::optional<PrimitiveHit> IntersectFoliage(const FoliageVolume& foliage, const Ray& ray,
                                             double t_max, double world_time_s) {
  double t_near = 0.0;
  double t_far = 0.0;
  bool side_near = false;
  bool side_far = false;
  if (!CylinderInterval(foliage.volume, ray, t_near, t_far, side_near, side_far)) {
    return std::nullopt;
  }
  if (t_far < 0.0) return std::nullopt;
  const double entry = std::max(t_near, 0.0);
  if (entry >= t_max) return std::nullopt;
  const double depth = -std::log(RayUniform(ray, world_time_s, foliage.index)) /
                       foliage.density_per_m;
  const double t = entry + depth;
  if (t > t_far || t >= t_max) return std::nullopt;
  // Leaves face every way; the one that stopped the ray faced back along it.
  return PrimitiveHit{t, -ray.direction};
}

double ExtrudedSurfaceDistance(double in_plane, double along_axis) {
  if (in_plane <= 0.0 && along_axis <= 0.0) return -std::max(in_plane, along_axis);
  const double a = std::max(in_plane, 0.0);
  const double b = std::max(along_axis, 0.0);
  return std::sqrt(a * a + b * b);
}

double DistanceToSurface(const OrientedBox& box, const Eigen::Vector3d& p) {
  const Eigen::Vector2d rel = p.head<2>() - box.center;
  const double u = box.cos_yaw * rel.x() + box.sin_yaw * rel.y();
  const double v = -box.sin_yaw * rel.x() + box.cos_yaw * rel.y();
  const double du = std::abs(u) - box.half_extent.x();
  const double dv = std::abs(v) - box.half_extent.y();
  // The rectangle's signed distance: outside the exact Euclidean one, inside the depth.
  const double in_plane = (du > 0.0 || dv > 0.0)
                              ? std::hypot(std::max(du, 0.0), std::max(dv, 0.0))
                              : std::max(du, dv);
  return ExtrudedSurfaceDistance(in_plane, std::abs(p.z() - box.z_center) - box.half_extent.z());
}

double DistanceToSurface(const VerticalCylinder& c, const Eigen::Vector3d& p) {
  const double radial = (p.head<2>() - c.center).norm() - c.radius;
  const double mid = 0.5 * (c.z_bottom + c.z_top);
  const double half = 0.5 * (c.z_top - c.z_bottom);
  return ExtrudedSurfaceDistance(radial, std::abs(p.z() - mid) - half);
}

double SignedDistanceToPolygon(const Eigen::Vector2d* v, std::uint32_t n,
                               const Eigen::Vector2d& p) {
  double nearest = kInfinity;
  for (std::uint32_t i = 0; i < n; ++i) {
    nearest = std::min(nearest, DistanceToSegment(v[i], v[(i + 1) % n], p));
  }
  return InsidePolygon(v, n, p.x(), p.y()) ? -nearest : nearest;
}

double DistanceToSurface(const Prism& prism, const Eigen::Vector2d* vertices,
                         const Eigen::Vector3d& p) {
  const double in_plane =
      SignedDistanceToPolygon(vertices + prism.first_vertex, prism.vertex_count, p.head<2>());
  const double mid = 0.5 * (prism.z_bottom + prism.z_top);
  const double half = 0.5 * (prism.z_top - prism.z_bottom);
  return ExtrudedSurfaceDistance(in_plane, std::abs(p.z() - mid) - half);
}

}  // namespace flat2d::hal::sim::internal
