// Data association of landmark SLAM (thesis 8.2): "if a feature is near a landmark L, then
// we add a factor between the last odometry node and L itself, otherwise a new landmark
// node is added". A feature predicted into the world by the current pose estimate is near
// a landmark when it passes every gate below; among the landmarks that pass, the one with
// the smallest gate-normalized distance (angle / angle gate + offset / offset gate) wins.
//
// Gates are fixed Euclidean thresholds, not Mahalanobis ones: the marginal covariance of a
// landmark is not available without inverting H, and the drift a gate must absorb (a few
// decimetres between optimizations) is the same for every landmark.
//
// Extent: a plane is infinite but a wall is not. Each plane track keeps the box, in its
// own plane, of everything associated with it; a feature whose box lies further than
// `plane_gap_m` from it along either in-plane axis is a different piece of wall, even when
// coplanar. So two collinear wall pieces with a doorway-sized gap between them merge (they
// are one plane, and one landmark constrains the trajectory better than two), and pieces
// further apart stay separate: the surfaces of a long street are rarely one true plane over
// tens of metres, and forcing them together would bend the trajectory to a wrong model.
// Lines keep the interval of their support along the line in the same way. Boxes are kept
// in the world frame at association time and not moved by later optimizations; the gap
// absorbs that correction.
//
// Points (key-points, thesis 8.2) have no extent and no orientation: a key-point is near a
// point landmark when its predicted position lies within `point_distance_m` of the
// landmark's current estimate, and the nearest such landmark wins. Nothing stops two
// key-points of one revolution from joining the same landmark; a detector's key-points
// closer than its support size (NARF's: 1 m) are rare, and the robust kernel takes the
// worse of the two.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "localization/landmarks/plane.hpp"
#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::localization::landmarks {

struct AssociationGates {
  double plane_normal_rad = 0.17;  // angle between the (oriented) normals, ~10 deg
  double plane_offset_m = 0.8;     // distance of the feature's centroid from the landmark plane
  double plane_gap_m = 2.0;        // largest gap between the boxes of feature and landmark
  double line_direction_rad = 0.17;  // angle between the (unoriented) directions
  double line_distance_m = 0.8;      // distance of the feature's point from the landmark line
  double line_gap_m = 2.0;           // largest gap between the supports along the line
  // Repeated structure (fence posts 2.5 m apart) aliases when the vehicle comes back with
  // more drift than half its spacing: the feature lands on the neighbour of its landmark.
  // A line landmark with another within line_distinct_m is therefore met again only within
  // line_revisit_travel_m of odometry travel since it was last seen; distinct lines (a
  // street light, a tree) may be met again after any travel. 0: no such rule.
  double line_distinct_m = 3.0;
  double line_revisit_travel_m = 20.0;
  // Distance of a key-point from a point landmark: a few times the 5 cm sigma of a key-point,
  // plus the drift between optimizations, under the ~1 m support that separates key-points.
  double point_distance_m = 0.5;
};

// What association needs of a plane landmark, in the world frame.
struct PlaneTrack {
  Plane plane;                     // oriented towards where it was first seen from
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // of the box: the first centroid
  Eigen::Vector3d axis1 = Eigen::Vector3d::UnitX();  // in-plane box axes
  Eigen::Vector3d axis2 = Eigen::Vector3d::UnitY();
  Eigen::Vector2d box_min = Eigen::Vector2d::Zero();
  Eigen::Vector2d box_max = Eigen::Vector2d::Zero();
};

struct LineTrack {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // of the line, the interval's origin
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  double along_min = 0.0;
  double along_max = 0.0;
  double last_seen_travel_m = 0.0;  // the odometry travel when a feature last joined it
  bool repeated = false;            // another line landmark within gates.line_distinct_m
};

// A track for a feature already in the world frame.
PlaneTrack StartPlaneTrack(const maps::features3d::PlaneFeature& world_feature);
LineTrack StartLineTrack(const maps::features3d::LineFeature& world_feature);

// The best track within the gates, or nullopt.
std::optional<int> AssociatePlane(const std::vector<PlaneTrack>& tracks,
                                  const maps::features3d::PlaneFeature& world_feature, const AssociationGates& gates);
// `travel_m`: the odometry travel now, for the repeated-structure rule.
std::optional<int> AssociateLine(const std::vector<LineTrack>& tracks, const maps::features3d::LineFeature& world_feature,
                                 const AssociationGates& gates, double travel_m);
// Adds `track` (a new landmark's, started at `travel_m`), marking it and the lines within
// gates.line_distinct_m of it as repeated structure.
void AddLineTrack(LineTrack track, double travel_m, const AssociationGates& gates, std::vector<LineTrack>& tracks);

// The nearest of `landmarks` (world positions) within gates.point_distance_m, or nullopt.
std::optional<int> AssociatePoint(const std::vector<Eigen::Vector3d>& landmarks, const Eigen::Vector3d& world_point,
                                  const AssociationGates& gates);

// Grows the track's extent by an associated feature.
void ExtendTrack(const maps::features3d::PlaneFeature& world_feature, PlaneTrack& track);
void ExtendTrack(const maps::features3d::LineFeature& world_feature, LineTrack& track);

}  // namespace flat2d::localization::landmarks
