// The scene's ground (internal to the Scene): a flat base plane plus ramps, and the lane
// markings painted on it.
//
// A ramp (scene.proto Ramp) is a convex solid standing on the base plane. In its own frame
// (u along `heading` from the middle of the bottom edge, v to the left) its cross-section
// rises from the base height at u = 0 with slope alpha over `run_m` (horizontal), stays
// level for `plateau_m`, then either falls back over another `run_m` (descend) or ends in a
// vertical drop-off face; it spans |v| <= width / 2 with vertical side faces. The ground's
// height at (x, y) is the highest of the base plane and every ramp over (x, y), so casting
// against the base plane and each ramp solid and keeping the nearest hit is exact.
#pragma once

#include <array>
#include <optional>

#include <Eigen/Core>

#include "hal/sim/scene.pb.h"
#include "hal/sim/scene_primitives.hpp"

namespace flat2d::hal::sim::internal {

struct RampSolid {
  ConvexSolid solid;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double cos_heading = 1.0;
  double sin_heading = 0.0;
  double tan_slope = 0.0;
  double run = 0.0;
  double plateau = 0.0;
  double length = 0.0;      // footprint length along u: 2 run + plateau, or run + plateau
  double half_width = 0.0;
  double base = 0.0;        // base ground height
  double rise = 0.0;        // plateau height above the base
  bool descend = false;
  std::array<Eigen::Vector2d, 4> footprint{};  // corners, counter-clockwise

  Eigen::Vector2d ToLocal(double x, double y) const;
  // Height and upward unit normal of the ramp's top surface over (x, y), if it covers it.
  std::optional<double> HeightAt(double x, double y) const;
  Eigen::Vector3d NormalAt(double x, double y) const;
  double DistanceToSurface(const Eigen::Vector3d& p) const;
};

// Builds the solid of a validated ramp on ground of height `base`.
RampSolid MakeRamp(const Ramp& ramp, double base);

// A straight piece of a lane marking.
struct LaneSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  double half_width = 0.0;
  std::uint8_t reflectivity = 0;

  bool Covers(const Eigen::Vector2d& p) const;
};

}  // namespace flat2d::hal::sim::internal
