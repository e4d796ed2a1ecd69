// The factor graph of landmark SLAM (thesis 8.2, graph-based SLAM of thesis 3.4): pose
// nodes (keyframes, world_T_vehicle), plane, line and point landmark nodes, and the factors
// between them: odometry between consecutive pose nodes, one observation factor per feature
// associated with a landmark. Plain data; LandmarkSlam builds it, OptimizeGraph moves its
// nodes.
//
// Landmarks are stored in an anchor frame, world_T_anchor, fixed when the landmark is
// created at the sensor's position then (axes of the world). The orthonormal line chart is
// singular for a line through its frame's origin and badly scaled far from it (line.hpp);
// the plane chart couples a tilt with an offset by the lever arm to the origin
// (landmark_factors.hpp, F2's Jacobian t^T B). Anchored where it was seen, every landmark
// is a few metres from its origin and off it, on a 1 km drive as on a 50 m one. A point
// (3D key-point, thesis 8.2) needs no chart, but is anchored alike so that its coordinates
// stay small and every landmark is handled one way.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "localization/landmarks/line.hpp"
#include "localization/landmarks/plane.hpp"

namespace flat2d::localization::landmarks {

struct PoseNode {
  Eigen::Isometry3d world_T_vehicle = Eigen::Isometry3d::Identity();
};

// Between pose nodes `from` and from + 1.
struct OdometryFactor {
  int from = 0;
  Eigen::Isometry3d from_T_to = Eigen::Isometry3d::Identity();  // dead-reckoned motion
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
};

struct PlaneNode {
  Eigen::Isometry3d world_T_anchor = Eigen::Isometry3d::Identity();
  Plane plane;           // in the anchor frame
  int observations = 0;  // factors joined to it
};

struct LineNode {
  Eigen::Isometry3d world_T_anchor = Eigen::Isometry3d::Identity();
  OrthonormalLine line;  // in the anchor frame, never through its origin
  int observations = 0;
};

struct PointNode {
  Eigen::Isometry3d world_T_anchor = Eigen::Isometry3d::Identity();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // in the anchor frame
  int observations = 0;
};

// A feature associated with a landmark, in the sensor frame of pose node `pose`.
struct PlaneObservation {
  int pose = 0;
  int landmark = 0;
  Plane measured;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // where on the plane it was seen
};

struct LineObservation {
  int pose = 0;
  int landmark = 0;
  PluckerLine measured;
  Eigen::Matrix4d information = Eigen::Matrix4d::Identity();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // where on the line it was seen
};

struct PointObservation {
  int pose = 0;
  int landmark = 0;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  // the key-point in the sensor frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

struct LandmarkGraph {
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();
  std::vector<PoseNode> poses;  // poses[0] is held fixed: the gauge
  std::vector<OdometryFactor> odometry;
  std::vector<PlaneNode> planes;
  std::vector<LineNode> lines;
  std::vector<PointNode> points;
  std::vector<PlaneObservation> plane_observations;
  std::vector<LineObservation> line_observations;
  std::vector<PointObservation> point_observations;
};

}  // namespace flat2d::localization::landmarks
