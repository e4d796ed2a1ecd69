#include "hal/sim/scene_footprint.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::hal::sim::internal {
namespace {

// Projections of the quad and the cell on `axis` overlap?
bool OverlapOnAxis(const std::array<Eigen::Vector2d, 4>& corners,
                   const Eigen::AlignedBox2d& cell, const Eigen::Vector2d& axis) {
  double quad_min = kInfinity;
  double quad_max = -kInfinity;
  for (const Eigen::Vector2d& c : corners) {
    const double p = c.dot(axis);
    quad_min = std::min(quad_min, p);
    quad_max = std::max(quad_max, p);
  }
  const Eigen::Vector2d centre = cell.center();
  const Eigen::Vector2d half = 0.5 * cell.sizes();
  const double c = centre.dot(axis);
  const double r = half.x() * std::abs(axis.x()) + half.y() * std::abs(axis.y());
  return quad_max >= c - r && quad_min <= c + r;
}

// Liang-Barsky: does the segment a-b touch the cell?
bool SegmentOverlapsCell(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::AlignedBox2d& cell) {
  double t0 = 0.0;
  double t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    bool entered = false;
    bool left = false;
    if (!ClipSlab(a[axis], d[axis], cell.min()[axis], cell.max()[axis], t0, t1, entered, left)) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::array<Eigen::Vector2d, 4> FootprintCorners(const OrientedBox& box) {
  const Eigen::Vector2d u = Eigen::Vector2d(box.cos_yaw, box.sin_yaw) * box.half_extent.x();
  const Eigen::Vector2d v = Eigen::Vector2d(-box.sin_yaw, box.cos_yaw) * box.half_extent.y();
  return {box.center - u - v, box.center + u - v, box.center + u + v, box.center - u + v};
}

bool QuadOverlapsCell(const std::array<Eigen::Vector2d, 4>& corners,
                      const Eigen::AlignedBox2d& cell) {
  if (!OverlapOnAxis(corners, cell, Eigen::Vector2d::UnitX()) ||
      !OverlapOnAxis(corners, cell, Eigen::Vector2d::UnitY())) {
    return false;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d edge = corners[(i + 1) % 4] - corners[i];
    if (edge.squaredNorm() == 0.0) continue;
    if (!OverlapOnAxis(corners, cell, Eigen::Vector2d(-edge.y(), edge.x()))) return false;
  }
  return true;
}

bool DiskOverlapsCell(const Eigen::Vector2d& center, double radius,
                      const Eigen::AlignedBox2d& cell) {
  const Eigen::Vector2d nearest = center.cwiseMax(cell.min()).cwiseMin(cell.max());
  return (nearest - center).squaredNorm() <= radius * radius;
}

bool PolygonOverlapsCell(const Eigen::Vector2d* vertices, std::uint32_t count,
                         const Eigen::AlignedBox2d& cell) {
  for (std::uint32_t i = 0; i < count; ++i) {
    if (SegmentOverlapsCell(vertices[i], vertices[(i + 1) % count], cell)) return true;
  }
  // No edge touches the cell: it is wholly inside or wholly outside.
  const Eigen::Vector2d c = cell.center();
  return InsidePolygon(vertices, count, c.x(), c.y());
}

bool CapsuleOverlapsCell(const LaneSegment& lane, const Eigen::AlignedBox2d& cell) {
  // Conservative: the segment's box grown by the half width on every side.
  const Eigen::Vector2d ab = lane.b - lane.a;
  const double len = ab.norm();
  const Eigen::Vector2d u = len > 0.0 ? Eigen::Vector2d(ab / len) : Eigen::Vector2d::UnitX();
  OrientedBox box;
  box.center = 0.5 * (lane.a + lane.b);
  box.cos_yaw = u.x();
  box.sin_yaw = u.y();
  box.half_extent = Eigen::Vector3d(0.5 * len + lane.half_width, lane.half_width, 0.0);
  return QuadOverlapsCell(FootprintCorners(box), cell);
}

Eigen::AlignedBox2d FootprintBounds(const std::array<Eigen::Vector2d, 4>& corners) {
  Eigen::AlignedBox2d bounds;
  for (const Eigen::Vector2d& c : corners) bounds.extend(c);
  return bounds;
}

Eigen::AlignedBox2d FootprintBounds(const VerticalCylinder& c) {
  const Eigen::Vector2d r = Eigen::Vector2d::Constant(c.radius);
  return {c.center - r, c.center + r};
}

Eigen::AlignedBox2d FootprintBounds(const LaneSegment& lane) {
  const Eigen::Vector2d r = Eigen::Vector2d::Constant(lane.half_width);
  return {lane.a.cwiseMin(lane.b) - r, lane.a.cwiseMax(lane.b) + r};
}

}  // namespace flat2d::hal::sim::internal
