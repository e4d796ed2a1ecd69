// The 3D features of a revolution (thesis 8.1.4): lines (posts, trunks, pillars) and
// planes (walls, facades), each with the cluster it was fitted to and an uncertainty.
//
// Covariances come from the cluster's own scatter: with N points and eigenvalues
// l1 <= l2 <= l3 along u1, u2, u3, a plane's residual variance is s^2 = l1, its normal tilts
// towards u2 and u3 with variances s^2 / (N l2) and s^2 / (N l3) and its offset at the
// centroid with s^2 / N; a line's offsets across it (along u1, u2) have l1 / N and l2 / N,
// its direction tilts l1 / (N l3) and l2 / (N l3). s^2 is floored at the sensor's noise so
// that a perfect fit is not infinitely certain.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace flat2d::maps::features3d {

// n . x + d = 0, n unit and facing the sensor, so d >= 0 is the plane's distance from it.
struct PlaneFeature {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double d = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d major_axis = Eigen::Vector3d::UnitZ();  // u3: the plane's longest extent
  Eigen::Vector2d half_extent = Eigen::Vector2d::Zero();   // of the points along u3, u2
  int points = 0;
  double residual_m = 0.0;  // e of Eq. 8.4
  // Of (tilt towards u2, tilt towards u3, offset along the normal at the centroid).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

// The line through `point` along unit `direction` (the cluster's mean, or the axis behind it
// for a thick pole: fitting.line_axis_min_radius_m, and u3).
struct LineFeature {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // pointing up where it can (z >= 0)
  Eigen::Vector3d across = Eigen::Vector3d::UnitX();     // u1; u2 = direction x across
  double half_length_m = 0.0;                            // of the points along the line
  int points = 0;
  double residual_m = 0.0;  // e of Eq. 8.4
  // Of (offset along u1, offset along u2, tilt towards u1, tilt towards u2) at `point`.
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();
};

struct FeatureSet {
  std::vector<PlaneFeature> planes;
  std::vector<LineFeature> lines;
};

}  // namespace flat2d::maps::features3d
