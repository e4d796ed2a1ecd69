#include "localization/landmarks/landmark_association.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flat2d::localization::landmarks {

namespace {

using maps::features3d::LineFeature;
using maps::features3d::PlaneFeature;

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// How far the interval [center - half, center + half] lies outside [low, high]; 0 if they meet.
double Gap(double center, double half, double low, double high) {
  return std::max({0.0, center - half - high, low - (center + half)});
}

// Centre and half-widths of the feature's box in the track's plane axes.
struct BoxInTrack {
  Eigen::Vector2d center;
  Eigen::Vector2d half;
};

BoxInTrack FeatureBox(const PlaneFeature& f, const PlaneTrack& track) {
  const Eigen::Vector3d u3 = f.major_axis;
  const Eigen::Vector3d u2 = f.normal.cross(u3);
  const Eigen::Vector3d offset = f.centroid - track.origin;
  BoxInTrack box;
  box.center = Eigen::Vector2d(track.axis1.dot(offset), track.axis2.dot(offset));
  box.half = Eigen::Vector2d(std::abs(u3.dot(track.axis1)) * f.half_extent(0) + std::abs(u2.dot(track.axis1)) * f.half_extent(1),
                             std::abs(u3.dot(track.axis2)) * f.half_extent(0) + std::abs(u2.dot(track.axis2)) * f.half_extent(1));
  return box;
}

}  // namespace

PlaneTrack StartPlaneTrack(const PlaneFeature& world_feature) {
  PlaneTrack track;
  track.plane = Plane{world_feature.normal, world_feature.d};
  track.origin = world_feature.centroid;
  const Eigen::Vector3d& n = world_feature.normal;
  Eigen::Vector3d axis1 = world_feature.major_axis - world_feature.major_axis.dot(n) * n;
  track.axis1 = axis1.norm() > 1e-6 ? axis1.normalized() : Eigen::Vector3d(n.unitOrthogonal());
  track.axis2 = n.cross(track.axis1);
  const BoxInTrack box = FeatureBox(world_feature, track);
  track.box_min = box.center - box.half;
  track.box_max = box.center + box.half;
  return track;
}

LineTrack StartLineTrack(const LineFeature& world_feature) {
  LineTrack track;
  track.point = world_feature.point;
  track.direction = world_feature.direction;
  track.along_min = -world_feature.half_length_m;
  track.along_max = world_feature.half_length_m;
  return track;
}

std::optional<int> AssociatePlane(const std::vector<PlaneTrack>& tracks, const PlaneFeature& f,
                                  const AssociationGates& gates) {
  std::optional<int> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const PlaneTrack& track = tracks[i];
    // The oriented normal: the two faces of a thin wall are different landmarks.
    const double angle = AngleBetween(f.normal, track.plane.normal);
    if (angle > gates.plane_normal_rad) continue;
    const double offset = std::abs(track.plane.normal.dot(f.centroid) + track.plane.distance);
    if (offset > gates.plane_offset_m) continue;
    const BoxInTrack box = FeatureBox(f, track);
    if (Gap(box.center(0), box.half(0), track.box_min(0), track.box_max(0)) > gates.plane_gap_m ||
        Gap(box.center(1), box.half(1), track.box_min(1), track.box_max(1)) > gates.plane_gap_m) {
      continue;
    }
    const double score = angle / gates.plane_normal_rad + offset / gates.plane_offset_m;
    if (score < best_score) {
      best_score = score;
      best = static_cast<int>(i);
    }
  }
  return best;
}

std::optional<int> AssociateLine(const std::vector<LineTrack>& tracks, const LineFeature& f,
                                 const AssociationGates& gates, double travel_m) {
  std::optional<int> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const LineTrack& track = tracks[i];
    if (track.repeated && gates.line_revisit_travel_m > 0.0 &&
        travel_m - track.last_seen_travel_m > gates.line_revisit_travel_m) {
      continue;
    }
    const double cosine = std::min(std::abs(f.direction.dot(track.direction)), 1.0);  // lines have no orientation
    const double angle = std::acos(cosine);
    if (angle > gates.line_direction_rad) continue;
    const Eigen::Vector3d offset = f.point - track.point;
    const double along = offset.dot(track.direction);
    const double distance = (offset - along * track.direction).norm();
    if (distance > gates.line_distance_m) continue;
    if (Gap(along, f.half_length_m * cosine, track.along_min, track.along_max) > gates.line_gap_m) continue;
    const double score = angle / gates.line_direction_rad + distance / gates.line_distance_m;
    if (score < best_score) {
      best_score = score;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void AddLineTrack(LineTrack track, double travel_m, const AssociationGates& gates, std::vector<LineTrack>& tracks) {
  track.last_seen_travel_m = travel_m;
  if (gates.line_distinct_m > 0.0) {
    for (LineTrack& other : tracks) {
      const Eigen::Vector3d offset = track.point - other.point;
      const double distance = (offset - offset.dot(other.direction) * other.direction).norm();
      if (distance >= gates.line_distinct_m) continue;
      other.repeated = true;
      track.repeated = true;
    }
  }
  tracks.push_back(track);
}

std::optional<int> AssociatePoint(const std::vector<Eigen::Vector3d>& landmarks, const Eigen::Vector3d& world_point,
                                  const AssociationGates& gates) {
  std::optional<int> best;
  double best_squared = gates.point_distance_m * gates.point_distance_m;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const double squared = (landmarks[i] - world_point).squaredNorm();
    if (squared <= best_squared) {
      best_squared = squared;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void ExtendTrack(const PlaneFeature& world_feature, PlaneTrack& track) {
  const BoxInTrack box = FeatureBox(world_feature, track);
  track.box_min = track.box_min.cwiseMin(box.center - box.half);
  track.box_max = track.box_max.cwiseMax(box.center + box.half);
}

void ExtendTrack(const LineFeature& world_feature, LineTrack& track) {
  const double along = (world_feature.point - track.point).dot(track.direction);
  const double half = world_feature.half_length_m * std::abs(world_feature.direction.dot(track.direction));
  track.along_min = std::min(track.along_min, along - half);
  track.along_max = std::max(track.along_max, along + half);
}

}  // namespace flat2d::localization::landmarks
