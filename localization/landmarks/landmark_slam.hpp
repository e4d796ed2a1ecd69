// Landmark SLAM with 3D planes, lines and key-points (thesis 8.2) as an incremental graph (thesis 3.4):
// "each incoming feature can generate either a new factor, or a new node, depending if we
// can associate it to an existing landmark or not".
//
// Steps of Add, per LiDAR revolution:
//  1. Keyframes: a pose node is added when the odometry has moved keyframe_distance_m or
//     turned keyframe_angle_rad since the last one, initialized from the last node's
//     estimate composed with the odometry's motion, and joined to it by an odometry factor
//     (graph_factors.hpp, O1) with planar information. The first revolution is the first
//     node, held fixed: the gauge (a prior of infinite weight).
//  2. Revolutions between keyframes are not skipped: their features are moved into the
//     sensor frame of the last pose node by the odometry's motion since it (under
//     keyframe_distance_m, where the odometry's error is a centimetre or two) and observed
//     from that node. Over a 0.5 m keyframe spacing this keeps all the data at a quarter of
//     the pose nodes; factors of one node on one landmark are counted as independent, which
//     overweights them against the odometry by up to the revolutions per keyframe.
//  3. Association (landmark_association.hpp): each feature predicted into the world with
//     the current estimate of its node either joins the nearest landmark within the gates
//     (a new factor) or starts a new landmark, anchored at the sensor's position
//     (landmark_graph.hpp), initialized from the feature.
//  4. Every optimize_every_nodes new pose nodes, a few Levenberg-Marquardt iterations
//     (graph_optimizer.hpp), robust kernel on the landmark factors, on a window: the newest
//     window_nodes pose nodes, every landmark they saw and every factor on those, older
//     poses fixed. The whole graph does not fit the budget: a landmark seen from 40 m of
//     road joins 80 keyframes into a dense block of the factor, so one sparse Cholesky of
//     an 850-keyframe graph takes seconds, and one of a 40-node window milliseconds. On a
//     revisit the old landmarks, held by their old fixed poses, pull the window onto the
//     old map; Finish then optimizes the whole graph, which spreads the drift of the loop.
//     Landmarks seen fewer than optimizer.min_landmark_observations times stay out.
// Information of each landmark factor comes from the feature's covariance, carried into
// the factor's error coordinates and floored (feature_measurement.hpp); a key-point's from
// the stated point_sigma_m (point_factor.hpp).
// Key-points (3D points in the sensor frame, e.g. NARF's for the thesis' comparison, Fig.
// 8.5-8.6) go through the same steps as point landmarks, beside or instead of the features.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/time.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/landmarks/feature_measurement.hpp"
#include "localization/landmarks/graph_factors.hpp"
#include "localization/landmarks/graph_optimizer.hpp"
#include "localization/landmarks/landmark_association.hpp"
#include "localization/landmarks/landmark_graph.hpp"
#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::localization::landmarks {

struct LandmarkSlamOptions {
  OdometryNoise odometry;     // information of the odometry factors (graph_factors.hpp)
  MeasurementFloors floors;   // added to every feature's own uncertainty (feature_measurement.hpp)
  AssociationGates gates;     // when a feature is "near" a landmark (landmark_association.hpp)
  OptimizerOptions optimizer;  // robust kernel (Cauchy, 3 sigma), LM damping, min observations
  double keyframe_distance_m = 0.5;  // a pose node every this much odometry travel ...
  double keyframe_angle_rad = 0.2;   // ... or this much odometry turn, whichever first
  int optimize_every_nodes = 10;     // optimization cadence, in new pose nodes
  int iterations_per_optimization = 3;  // LM iterations at each of those
  // Poses those optimizations move: the newest window_nodes; older ones hold still. 0: all.
  int window_nodes = 40;
  int final_iterations = 30;           // LM iterations in Finish (stops earlier at convergence)
  // Per axis, of every key-point: a detector gives a position and no covariance. 5 cm: a
  // range image pixel of 0.2 deg at 15 m, and the range noise of a Velodyne (~2 cm).
  double point_sigma_m = 0.05;
};

struct LandmarkSlamStats {
  int revolutions = 0;
  int pose_nodes = 0;
  int plane_landmarks = 0;  // created, including those seen once and never solved
  int line_landmarks = 0;
  int point_landmarks = 0;
  int plane_factors = 0;  // plane observations in the graph
  int line_factors = 0;
  int point_factors = 0;
  int new_landmarks = 0;  // features that started a landmark
  int associations = 0;   // features that joined an existing landmark
  int rejected_features = 0;  // not finite or without unit axes: dropped (key-points: not finite)
  int optimizations = 0;
  int iterations = 0;             // LM steps over every optimization
  int downweighted_factors = 0;   // robust weight < 1/2 at the last optimization
  double final_cost = 0.0;        // robust cost after the last optimization
  double solve_ms_total = 0.0;    // in OptimizeGraph
  double last_solve_ms = 0.0;     // of the last optimization (Finish's, once it ran)
  double backend_ms_total = 0.0;  // in Add and Finish, association and solves
};

class LandmarkSlam {
 public:
  LandmarkSlam(const LandmarkSlamOptions& options, const Eigen::Isometry3d& vehicle_T_sensor);

  // One LiDAR revolution: its time, the vehicle's dead-reckoned pose (world_T_vehicle from
  // CAN odometry, an SE(3) lift of a planar pose), its features and its key-points in the
  // sensor frame.
  void Add(TimeNs stamp, const Eigen::Isometry3d& odometry_world_T_vehicle, const maps::features3d::FeatureSet& features,
           std::span<const Eigen::Vector3d> keypoints = {});

  // The final optimization of the whole graph.
  void Finish();

  // world_T_vehicle at every revolution added, in order: pose nodes as optimized,
  // revolutions between them by the odometry's motion from the previous node.
  std::vector<hal::trajectory::StampedPose> Trajectory() const;

  // The landmarks in the world frame, with how many features were associated with each
  // (landmarks seen fewer than optimizer.min_landmark_observations times were never
  // optimized). The centroid and the point are the mean of where the landmark was seen,
  // projected onto it.
  struct PlaneLandmark {
    Plane plane;
    int observations = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  };
  struct LineLandmark {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
    int observations = 0;
  };
  struct PointLandmark {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    int observations = 0;
  };
  std::vector<PlaneLandmark> Planes() const;
  std::vector<LineLandmark> Lines() const;
  std::vector<PointLandmark> Points() const;

  const LandmarkSlamStats& stats() const { return stats_; }
  const LandmarkGraph& graph() const { return graph_; }

 private:
  struct Revolution {
    TimeNs stamp = 0;
    int node = 0;
    Eigen::Isometry3d node_T_vehicle = Eigen::Isometry3d::Identity();  // odometry since the node
  };

  bool AddPoseNodeIfKeyframe(const Eigen::Isometry3d& odometry_world_T_vehicle);
  void AddPlane(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const maps::features3d::PlaneFeature& feature);
  void AddLine(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const maps::features3d::LineFeature& feature);
  void AddPoint(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const Eigen::Vector3d& keypoint);
  void Optimize(int iterations, int first_free_pose);
  void RefreshTracks();
  Eigen::Isometry3d WorldTSensor(int node) const;

  const LandmarkSlamOptions options_;
  LandmarkGraph graph_;
  Eigen::Isometry3d sensor_T_vehicle_;
  std::vector<PlaneTrack> plane_tracks_;  // parallel to graph_.planes
  std::vector<LineTrack> line_tracks_;    // parallel to graph_.lines
  std::vector<Eigen::Vector3d> point_tracks_;  // world positions, parallel to graph_.points
  std::vector<Revolution> revolutions_;
  Eigen::Isometry3d last_node_odometry_ = Eigen::Isometry3d::Identity();
  int nodes_since_optimization_ = 0;
  double travel_m_ = 0.0;  // odometry travel over the pose nodes so far
  LandmarkSlamStats stats_;
};

}  // namespace flat2d::localization::landmarks
