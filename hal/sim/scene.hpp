// A simulated world ready for ray casting: the primitives of a SceneDescription
// (scene.proto) compiled into flat arrays with an acceleration grid, the ground with its
// ramps, and the moving objects at any world time.
//
// Cast answers where a LiDAR ray first meets a surface; GroundHeight/GroundNormal give the
// vehicle its z, pitch and roll; DistanceToSurface lets tests check that decoded points lie
// on the scene. A Scene is immutable after Create and safe to share between threads.
//
// How Cast works (scene.cpp): the base ground plane analytically; then a 2D DDA walk over a
// uniform grid of 3 m cells listing the static solids and ramps whose footprints touch each
// cell (scene_grid.hpp), stopping at the first cell that holds the nearest hit; then the
// moving objects at the given world time, behind a conservative per-thread prefilter
// (scene_movers.hpp). Intersections are exact (scene_primitives.hpp): solids are hit from
// either side (a ray starting inside a box meets the face it leaves through), normals face
// the ray origin, and a foliage hit's normal is minus the ray direction. Foliage stops a ray
// at an exponential depth drawn from a hash of the ray, the time and the crown, so Cast is a
// pure function of its arguments: the same call always gives the same answer.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim {

enum class SurfaceKind : std::uint8_t {
  kGround,
  kStatic,   // boxes, walls, buildings, cylinders, bars, curbs
  kFoliage,
  kMoving,
};

struct SurfaceHit {
  double range_m = 0.0;                              // along the (unit) direction
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, facing the ray origin
  std::uint8_t reflectivity = 0;
  SurfaceKind kind = SurfaceKind::kGround;
};

class Scene {
 public:
  // Validates the description (finite numbers, positive sizes, >= 2 points per polyline,
  // simple polygons, slopes below 45 deg, ...) and builds the acceleration structure.
  // Errors name the offending element, e.g. "walls[3].points: needs at least 2 points".
  static Result<Scene> Create(const SceneDescription& description);

  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  // The first surface a ray from `origin` along unit `direction` meets within max_range_m,
  // with moving objects where they are at `world_time_s`. Allocates nothing.
  std::optional<SurfaceHit> Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                 double max_range_m, double world_time_s) const;

  // Height and upward unit normal of the ground (base height and ramps) at (x, y). The height
  // is continuous along a descending ramp; the normal is each planar piece's own (it jumps
  // at the slope breaks and the ramp's edges).
  double GroundHeight(double x, double y) const;
  Eigen::Vector3d GroundNormal(double x, double y) const;

  // Distance from `point` to the nearest surface (ground, static, moving at world_time_s;
  // foliage counts as its volume: 0 inside). For tests of the LiDAR round trip.
  double DistanceToSurface(const Eigen::Vector3d& point, double world_time_s) const;

  // The XY box that holds every static primitive, ramp, lane and drive waypoint (empty for a
  // scene with none: flat ground only).
  Eigen::AlignedBox2d bounds() const;

  const SceneDescription& description() const;

 private:
  struct Impl;
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace flat2d::hal::sim
