// Exact ray intersection with the scene's solids (internal to the Scene).
//
// Every solid is closed and hit from either side: a ray that starts outside meets the face
// it enters through, a ray that starts inside meets the face it leaves through, and the
// returned normal always faces the ray origin (n . direction <= 0). Convex solids (oriented
// boxes, vertical cylinders, ramp wedges) use Kay-Kajiya slab clipping: the ray's parameter
// interval is cut by each face's half-space and the face that set the surviving bound is
// the one hit. Extruded polygons, which may be concave, test each side face and both caps.
//
// The functions are inline because Cast calls them millions of times a second; they
// allocate nothing and return the hit distance t along a unit direction, t in [0, t_max).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace flat2d::hal::sim::internal {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Below this a direction component counts as parallel to a face (avoids 0 * inf = NaN).
inline constexpr double kParallelEpsilon = 1e-12;

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
};

struct PrimitiveHit {
  double t = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, facing the ray origin
};

// A box with vertical sides turned by yaw about z: boxes, wall and curb segments, bars.
struct OrientedBox {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double cos_yaw = 1.0;
  double sin_yaw = 0.0;
  Eigen::Vector3d half_extent = Eigen::Vector3d::Zero();  // along yaw, across, vertical
  double z_center = 0.0;
  std::uint8_t reflectivity = 0;

  double z_bottom() const { return z_center - half_extent.z(); }
  double z_top() const { return z_center + half_extent.z(); }
};

struct VerticalCylinder {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double z_bottom = 0.0;
  double z_top = 0.0;
  std::uint8_t reflectivity = 0;
};

// A simple polygon extruded from z_bottom to z_top; vertices live in a shared pool.
struct Prism {
  std::uint32_t first_vertex = 0;
  std::uint32_t vertex_count = 0;
  double z_bottom = 0.0;
  double z_top = 0.0;
  Eigen::Vector2d min_xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_xy = Eigen::Vector2d::Zero();
  std::uint8_t reflectivity = 0;
};

// A volume of leaves: a ray inside it stops after an exponential depth (mean 1 / density).
struct FoliageVolume {
  VerticalCylinder volume;
  double density_per_m = 1.0;
  std::uint32_t index = 0;  // salts the per-ray draw so two crowns are independent
};

// A convex solid as an intersection of half-spaces n . x <= d (n unit, outward).
struct HalfSpace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};

struct ConvexSolid {
  std::array<HalfSpace, 8> faces{};
  int face_count = 0;
};

// Flips an outward normal so that it faces the ray origin.
inline Eigen::Vector3d FacingOrigin(const Eigen::Vector3d& normal, const Eigen::Vector3d& dir) {
  return normal.dot(dir) > 0.0 ? Eigen::Vector3d(-normal) : normal;
}

// Cuts the interval [t_near, t_far] by the slab lo <= o + t d <= hi along one axis.
// Returns false when the ray misses the slab. `entered`/`left` report which bound moved.
inline bool ClipSlab(double o, double d, double lo, double hi, double& t_near, double& t_far,
                     bool& entered, bool& left) {
  entered = false;
  left = false;
  if (std::abs(d) < kParallelEpsilon) return o >= lo && o <= hi;
  const double inv = 1.0 / d;
  double t0 = (lo - o) * inv;
  double t1 = (hi - o) * inv;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_near) {
    t_near = t0;
    entered = true;
  }
  if (t1 < t_far) {
    t_far = t1;
    left = true;
  }
  return t_near <= t_far;
}

// Picks the entry face (origin outside) or the exit face (origin inside) of a convex
// interval; `near_axis`/`far_axis` index the face normals supplied by the caller.
inline std::optional<double> ChooseConvexHit(double t_near, double t_far, double t_max,
                                             bool& use_far) {
  if (t_far < 0.0) return std::nullopt;
  use_far = t_near < 0.0;
  const double t = use_far ? t_far : t_near;
  if (t >= t_max) return std::nullopt;
  return t;
}

inline std::optional<PrimitiveHit> Intersect(const OrientedBox& box, const Ray& ray,
                                             double t_max) {
  const Eigen::Vector2d rel = ray.origin.head<2>() - box.center;
  const Eigen::Vector3d o(box.cos_yaw * rel.x() + box.sin_yaw * rel.y(),
                          -box.sin_yaw * rel.x() + box.cos_yaw * rel.y(),
                          ray.origin.z() - box.z_center);
  const Eigen::Vector3d& w = ray.direction;
  const Eigen::Vector3d d(box.cos_yaw * w.x() + box.sin_yaw * w.y(),
                          -box.sin_yaw * w.x() + box.cos_yaw * w.y(), w.z());
  double t_near = -kInfinity;
  double t_far = kInfinity;
  int near_axis = -1;
  int far_axis = -1;
  for (int axis = 0; axis < 3; ++axis) {
    bool entered = false;
    bool left = false;
    const double h = box.half_extent[axis];
    if (!ClipSlab(o[axis], d[axis], -h, h, t_near, t_far, entered, left)) return std::nullopt;
    if (entered) near_axis = axis;
    if (left) far_axis = axis;
  }
  bool use_far = false;
  const auto t = ChooseConvexHit(t_near, t_far, t_max, use_far);
  if (!t) return std::nullopt;
  const int axis = use_far ? far_axis : near_axis;
  if (axis < 0) return std::nullopt;  // only with a zero-extent box
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  local[axis] = d[axis] > 0.0 ? -1.0 : 1.0;  // the face towards the origin
  const Eigen::Vector3d normal(box.cos_yaw * local.x() - box.sin_yaw * local.y(),
                               box.sin_yaw * local.x() + box.cos_yaw * local.y(), local.z());
  return PrimitiveHit{*t, normal};
}

// The parameter interval in which the ray is inside the cylinder; false when it never is.
// `side_near`/`side_far` tell whether the bound comes from the curved side or a cap.
inline bool CylinderInterval(const VerticalCylinder& c, const Ray& ray, double& t_near,
                             double& t_far, bool& side_near, bool& side_far) {
  const Eigen::Vector2d p = ray.origin.head<2>() - c.center;
  const Eigen::Vector2d d = ray.direction.head<2>();
  const double a = d.squaredNorm();
  const double r2 = c.radius * c.radius;
  if (a < kParallelEpsilon * kParallelEpsilon) {
    if (p.squaredNorm() > r2) return false;
    t_near = -kInfinity;
    t_far = kInfinity;
    side_near = side_far = false;
  } else {
    const double b = p.dot(d);  // half of the usual b
    const double cc = p.squaredNorm() - r2;
    const double disc = b * b - a * cc;
    if (disc < 0.0) return false;
    // Stable roots: q = -(b + sign(b) sqrt(disc)); t = q / a and cc / q.
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a;
    double t1 = q != 0.0 ? cc / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    t_near = t0;
    t_far = t1;
    side_near = side_far = true;
  }
  bool entered = false;
  bool left = false;
  if (!ClipSlab(ray.origin.z(), ray.direction.z(), c.z_bottom, c.z_top, t_near, t_far, entered,
                left)) {
    return false;
  }
  if (entered) side_near = false;
  if (left) side_far = false;
  return true;
}

inline std::optional<PrimitiveHit> Intersect(const VerticalCylinder& c, const Ray& ray,
                                             double t_max) {
  double t_near = 0.0;
  double t_far = 0.0;
  bool side_near = false;
  bool side_far = false;
  if (!CylinderInterval(c, ray, t_near, t_far, side_near, side_far)) return std::nullopt;
  bool use_far = false;
  const auto t = ChooseConvexHit(t_near, t_far, t_max, use_far);
  if (!t) return std::nullopt;
  const bool side = use_far ? side_far : side_near;
  Eigen::Vector3d outward = Eigen::Vector3d::UnitZ();
  if (side) {
    const Eigen::Vector2d radial =
        (ray.origin.head<2>() + *t * ray.direction.head<2>() - c.center) / c.radius;
    outward = Eigen::Vector3d(radial.x(), radial.y(), 0.0).normalized();
  }
  return PrimitiveHit{*t, FacingOrigin(outward, ray.direction)};
}

inline std::optional<PrimitiveHit> Intersect(const ConvexSolid& solid, const Ray& ray,
                                             double t_max) {
  double t_near = -kInfinity;
  double t_far = kInfinity;
  int near_face = -1;
  int far_face = -1;
  for (int i = 0; i < solid.face_count; ++i) {
    const HalfSpace& face = solid.faces[static_cast<std::size_t>(i)];
    const double denom = face.normal.dot(ray.direction);
    const double room = face.offset - face.normal.dot(ray.origin);  // >= 0: origin inside
    if (std::abs(denom) < kParallelEpsilon) {
      if (room < 0.0) return std::nullopt;
      continue;
    }
    const double t = room / denom;
    if (denom < 0.0) {
      if (t > t_near) {
        t_near = t;
        near_face = i;
      }
    } else if (t < t_far) {
      t_far = t;
      far_face = i;
    }
    if (t_near > t_far) return std::nullopt;
  }
  bool use_far = false;
  const auto t = ChooseConvexHit(t_near, t_far, t_max, use_far);
  const int face = use_far ? far_face : near_face;
  if (!t || face < 0) return std::nullopt;
  const Eigen::Vector3d& n = solid.faces[static_cast<std::size_t>(face)].normal;
  return PrimitiveHit{*t, FacingOrigin(n, ray.direction)};
}

// Crossing-number test; points exactly on an edge may go either way.
inline bool InsidePolygon(const Eigen::Vector2d* v, std::uint32_t n, double x, double y) {
  bool inside = false;
  for (std::uint32_t i = 0, j = n - 1; i < n; j = i++) {
    if ((v[i].y() > y) != (v[j].y() > y)) {
      const double x_cross = v[j].x() + (y - v[j].y()) * (v[i].x() - v[j].x()) /
                                            (v[i].y() - v[j].y());
      if (x < x_cross) inside = !inside;
    }
  }
  return inside;
}

std::optional<PrimitiveHit> IntersectPrism(const Prism& prism, const Eigen::Vector2d* vertices,
                                           const Ray& ray, double t_max);

// Where a ray stops inside a leaf volume: at an exponential depth past the entry point
// (the origin when it starts inside), drawn from a hash of the ray, the time and the
// volume, so the same ray at the same time always stops at the same place.
std::optional<PrimitiveHit> IntersectFoliage(const FoliageVolume& foliage, const Ray& ray,
                                             double t_max, double world_time_s);

// Distance from a point to the surface of each solid (0 on it, positive inside too).
double DistanceToSurface(const OrientedBox& box, const Eigen::Vector3d& p);
double DistanceToSurface(const VerticalCylinder& c, const Eigen::Vector3d& p);
double DistanceToSurface(const Prism& prism, const Eigen::Vector2d* vertices,
                         const Eigen::Vector3d& p);
// Signed distance from (x, y) to a polygon's boundary: negative inside.
double SignedDistanceToPolygon(const Eigen::Vector2d* v, std::uint32_t n,
                               const Eigen::Vector2d& p);
// Distance to the surface of a solid whose cross-section has signed distance `in_plane`
// and whose extrusion axis has signed distance `along_axis` (both negative inside).
double ExtrudedSurfaceDistance(double in_plane, double along_axis);

}  // namespace flat2d::hal::sim::internal
