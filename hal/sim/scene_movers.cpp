#include "hal/sim/scene_movers.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::hal::sim::internal {

MoverTrack::MoverTrack(const MovingObject& description, double base, std::uint8_t reflectivity)
    : speed_(description.speed_mps()),
      start_s_(description.start_s()),
      loop_(description.loop()),
      is_box_(description.has_box()),
      reflectivity_(reflectivity) {
  for (const Vec2& p : description.path()) {
    const Eigen::Vector2d point(p.x(), p.y());
    if (points_.empty() || point != points_.back()) points_.push_back(point);
  }
  if (loop_ && points_.size() > 1 && points_.front() != points_.back()) {
    points_.push_back(points_.front());
  }
  arc_.push_back(0.0);
  for (std::size_t i = 1; i < points_.size(); ++i) {
    arc_.push_back(arc_.back() + (points_[i] - points_[i - 1]).norm());
  }
  double reach = 0.0;  // how far the shape sticks out from its centre in XY
  if (is_box_) {
    const Box& box = description.box();
    half_extent_ = 0.5 * Eigen::Vector3d(box.length_m(), box.width_m(), box.height_m());
    z_bottom_ = base + box.bottom();
    z_top_ = z_bottom_ + box.height_m();
    reach = half_extent_.head<2>().norm();
  } else {
    const Cylinder& cylinder = description.cylinder();
    radius_ = cylinder.radius_m();
    z_bottom_ = base + cylinder.bottom();
    z_top_ = z_bottom_ + cylinder.height_m();
    reach = radius_;
  }
  for (std::size_t i = 1; i < points_.size(); ++i) {
    headings_.push_back((points_[i] - points_[i - 1]).normalized());
  }
  // Bounded table: at most kMaxSamples samples, at least 0.5 m apart.
  constexpr double kMaxSamples = 8192.0;
  sample_step_ = std::max(0.5, arc_.back() / kMaxSamples);
  for (std::size_t k = 0; static_cast<double>(k) * sample_step_ <= arc_.back() + sample_step_; ++k) {
    samples_.push_back(PlacementAt(std::min(static_cast<double>(k) * sample_step_, arc_.back())).position);
  }
  reject_radius_ = reach + sample_step_ + 1e-9;
  inv_step_ = 1.0 / sample_step_;
  length_ = arc_.back();
  inv_length_ = length_ > 0.0 ? 1.0 / length_ : 0.0;  // the centre is within one step of a sample
}

MoverTrack::Placement MoverTrack::PlacementAt(double arc) const {
  if (points_.size() < 2) return {points_.front(), Eigen::Vector2d::UnitX()};
  // The segment [arc_[i], arc_[i + 1]] that holds s; every segment has positive length.
  const auto after = std::upper_bound(arc_.begin(), arc_.end(), arc);
  const std::size_t i = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - arc_.begin() - 1, 0)),
      points_.size() - 2);
  return {points_[i] + (arc - arc_[i]) * headings_[i], headings_[i]};
}

MoverPose MoverTrack::PoseAt(double world_time_s) const {
  const Placement p = PlacementAt(ArcAt(world_time_s));
  return {p.position, std::atan2(p.heading.y(), p.heading.x())};
}

OrientedBox MoverTrack::BoxAt(const Placement& placement) const {
  OrientedBox box;
  box.center = placement.position;
  box.cos_yaw = placement.heading.x();
  box.sin_yaw = placement.heading.y();
  box.half_extent = half_extent_;
  box.z_center = 0.5 * (z_bottom_ + z_top_);
  return box;
}

VerticalCylinder MoverTrack::CylinderAt(const Placement& placement) const {
  return VerticalCylinder{placement.position, radius_, z_bottom_, z_top_, reflectivity_};
}

std::optional<PrimitiveHit> MoverTrack::IntersectAt(const Ray& ray, double t_max,
                                                    double arc) const {
  const Placement placement = PlacementAt(arc);
  if (is_box_) return internal::Intersect(BoxAt(placement), ray, t_max);
  return internal::Intersect(CylinderAt(placement), ray, t_max);
}

std::optional<PrimitiveHit> MoverTrack::Intersect(const Ray& ray, double t_max,
                                                  double world_time_s) const {
  const double arc = ArcAt(world_time_s);
  if (!MayMeet(RayBounds(ray, t_max), arc)) return std::nullopt;
  return IntersectAt(ray, t_max, arc);
}

double MoverTrack::DistanceToSurface(const Eigen::Vector3d& p, double world_time_s) const {
  const Placement placement = PlacementAt(ArcAt(world_time_s));
  if (is_box_) return internal::DistanceToSurface(BoxAt(placement), p);
  return internal::DistanceToSurface(CylinderAt(placement), p);
}

const MoverWindow& MoverWindow::For(std::uint64_t scene_id, const std::vector<MoverTrack>& movers,
                                    double world_time_s) {
  thread_local MoverWindow window;
  if (window.scene_id_ == scene_id && world_time_s >= window.start_s_ &&
      world_time_s < window.end_s_) {
    return window;
  }
  window.scene_id_ = scene_id;
  window.start_s_ = std::floor(world_time_s / kWindowS) * kWindowS;
  window.end_s_ = window.start_s_ + kWindowS;
  if (!(world_time_s >= window.start_s_ && world_time_s < window.end_s_)) {  // huge or NaN time
    window.start_s_ = window.end_s_ = world_time_s;
    window.count_ = 0;
    return window;
  }
  const double middle = window.start_s_ + 0.5 * kWindowS;
  window.count_ = std::min(movers.size(), kCapacity);
  for (std::size_t i = 0; i < window.count_; ++i) {
    const MoverTrack& m = movers[i];
    const Eigen::Vector2d c = m.CenterAt(m.ArcAt(middle));
    // Arc travelled in half a window bounds the straight-line distance; 1 mm of slack
    // covers rounding in the window's bounds.
    window.extents_[i] = {c.x(), c.y(), m.reach() + m.speed() * 0.5 * kWindowS + 1e-3,
                          m.z_bottom(), m.z_top()};
  }
  return window;
}

}  // namespace flat2d::hal::sim::internal
