// Moving objects (internal to the Scene): a box or cylinder sliding along a polyline at
// constant speed (scene.proto MovingObject).
//
// At world time t the object is at arc length s = speed (t - start_s) along the path,
// clamped to [0, length], or wrapped modulo the length of the closed path (last point
// joined back to the first) when `loop` is set. A box's yaw is the heading of the path
// segment it is on.
//
// Casting must be cheap for the many rays that pass far from an object, without caching
// anything between calls (Cast is pure and thread-safe). So the path is sampled at
// construction every `sample_step_` metres of arc length; at time t the object's centre is
// within sample_step_ of the sample at floor(s / step), so a ray whose XY segment passes
// farther than (reach + step) from that sample cannot touch it. Only the rest get the exact
// placement and the exact box or cylinder test.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "hal/sim/scene.pb.h"
#include "hal/sim/scene_primitives.hpp"

namespace flat2d::hal::sim::internal {

// The box a ray's segment [0, t_max] spans, computed once per ray for all movers.
struct RayBounds {
  Eigen::Vector2d min_xy;
  Eigen::Vector2d max_xy;
  double min_z;
  double max_z;

  RayBounds(const Ray& ray, double t_max) {
    const Eigen::Vector3d end = ray.origin + t_max * ray.direction;
    min_xy = ray.origin.head<2>().cwiseMin(end.head<2>());
    max_xy = ray.origin.head<2>().cwiseMax(end.head<2>());
    min_z = std::min(ray.origin.z(), end.z());
    max_z = std::max(ray.origin.z(), end.z());
  }
};

struct MoverPose {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double yaw = 0.0;
};

class MoverTrack {
 public:
  // `description` must be valid; `base` is the ground's base height.
  MoverTrack(const MovingObject& description, double base, std::uint8_t reflectivity);

  MoverPose PoseAt(double world_time_s) const;
  // Arc length along the path at a world time (clamped, or wrapped for a loop).
  double ArcAt(double world_time_s) const {
    double s = speed_ * (world_time_s - start_s_);
    if (loop_) s -= length_ * std::floor(s * inv_length_);
    return std::clamp(s, 0.0, length_);
  }
  // False when a ray within `bounds` cannot touch the object while it is at `arc`.
  bool MayMeet(const RayBounds& bounds, double arc) const {
    if (bounds.max_z < z_bottom_ || bounds.min_z > z_top_) return false;
    const Eigen::Vector2d& c = samples_[std::min(static_cast<std::size_t>(arc * inv_step_),
                                                 samples_.size() - 1)];
    return c.x() + reject_radius_ >= bounds.min_xy.x() &&
           c.x() - reject_radius_ <= bounds.max_xy.x() &&
           c.y() + reject_radius_ >= bounds.min_xy.y() &&
           c.y() - reject_radius_ <= bounds.max_xy.y();
  }
  // The exact hit with the object at `arc` (from ArcAt).
  std::optional<PrimitiveHit> IntersectAt(const Ray& ray, double t_max, double arc) const;
  std::optional<PrimitiveHit> Intersect(const Ray& ray, double t_max,
                                        double world_time_s) const;
  double DistanceToSurface(const Eigen::Vector3d& p, double world_time_s) const;
  std::uint8_t reflectivity() const { return reflectivity_; }
  double speed() const { return speed_; }
  double reach() const { return reject_radius_ - sample_step_; }
  double z_bottom() const { return z_bottom_; }
  double z_top() const { return z_top_; }
  Eigen::Vector2d CenterAt(double arc) const { return PlacementAt(arc).position; }

 private:
  struct Placement {
    Eigen::Vector2d position;
    Eigen::Vector2d heading;  // unit
  };
  Placement PlacementAt(double arc) const;
  OrientedBox BoxAt(const Placement& placement) const;
  VerticalCylinder CylinderAt(const Placement& placement) const;

  std::vector<Eigen::Vector2d> points_;  // consecutive duplicates removed; closed for a loop
  std::vector<double> arc_;              // arc length at each point
  std::vector<Eigen::Vector2d> headings_;  // unit direction of each segment
  std::vector<Eigen::Vector2d> samples_;   // centre every sample_step_ of arc length
  double sample_step_ = 1.0;
  double inv_step_ = 1.0;
  double length_ = 0.0;
  double inv_length_ = 0.0;  // 0 for a zero-length path
  double reject_radius_ = 0.0;             // reach + sample_step_
  double speed_ = 0.0;
  double start_s_ = 0.0;
  bool loop_ = false;
  bool is_box_ = true;
  Eigen::Vector3d half_extent_ = Eigen::Vector3d::Zero();  // box
  double radius_ = 0.0;                                    // cylinder
  double z_bottom_ = 0.0;
  double z_top_ = 0.0;
  std::uint8_t reflectivity_ = 0;
};

// Where each moving object can be during a short window of world time: a circle around its
// centre at mid-window, grown by the distance it can travel in half a window. Kept per
// thread (consecutive rays of a LiDAR have nearly the same time), refilled when a ray's
// time leaves the window or another scene asks; it only rejects rays that cannot touch an
// object, so results never depend on what it holds. Fixed size: no allocation.
class MoverWindow {
 public:
  static constexpr std::size_t kCapacity = 64;  // movers beyond it take the direct test
  static constexpr double kWindowS = 0.02;

  struct Extent {
    double x, y, radius, z_bottom, z_top;
  };

  // The window holding `world_time_s` for the scene `scene_id`.
  static const MoverWindow& For(std::uint64_t scene_id, const std::vector<MoverTrack>& movers,
                                double world_time_s);

  std::size_t count() const { return count_; }
  bool MayMeet(std::size_t i, const RayBounds& b) const {
    const Extent& e = extents_[i];
    return b.max_z >= e.z_bottom && b.min_z <= e.z_top && e.x + e.radius >= b.min_xy.x() &&
           e.x - e.radius <= b.max_xy.x() && e.y + e.radius >= b.min_xy.y() &&
           e.y - e.radius <= b.max_xy.y();
  }

 private:
  std::uint64_t scene_id_ = 0;  // 0: empty
  double start_s_ = 0.0;
  double end_s_ = 0.0;
  std::size_t count_ = 0;
  std::array<Extent, kCapacity> extents_{};
};

}  // namespace flat2d::hal::sim::internal
