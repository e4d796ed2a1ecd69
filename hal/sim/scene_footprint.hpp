// Footprints of the scene's solids on the XY plane (internal to the Scene): which
// axis-aligned cells a solid's footprint overlaps. The acceleration grid uses them to file
// each solid under the cells it touches, and the truth map to rasterize structure, so a
// solid thinner than a cell still marks the cell it stands in.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/sim/scene_ground.hpp"
#include "hal/sim/scene_primitives.hpp"

namespace flat2d::hal::sim::internal {

// Corners of a box's footprint, counter-clockwise.
std::array<Eigen::Vector2d, 4> FootprintCorners(const OrientedBox& box);

// Separating-axis test of a convex quadrilateral (corners in order) against a cell.
bool QuadOverlapsCell(const std::array<Eigen::Vector2d, 4>& corners,
                      const Eigen::AlignedBox2d& cell);
bool DiskOverlapsCell(const Eigen::Vector2d& center, double radius,
                      const Eigen::AlignedBox2d& cell);
bool PolygonOverlapsCell(const Eigen::Vector2d* vertices, std::uint32_t count,
                         const Eigen::AlignedBox2d& cell);
bool CapsuleOverlapsCell(const LaneSegment& lane, const Eigen::AlignedBox2d& cell);

Eigen::AlignedBox2d FootprintBounds(const std::array<Eigen::Vector2d, 4>& corners);
Eigen::AlignedBox2d FootprintBounds(const VerticalCylinder& c);
Eigen::AlignedBox2d FootprintBounds(const LaneSegment& lane);

}  // namespace flat2d::hal::sim::internal
