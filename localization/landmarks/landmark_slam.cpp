#include "localization/landmarks/landmark_slam.hpp"

#include <algorithm>
#include <chrono>

#include "localization/landmarks/point_factor.hpp"

namespace flat2d::localization::landmarks {

namespace {

using maps::features3d::LineFeature;
using maps::features3d::PlaneFeature;

// A frame with the world's axes at `position`: where a landmark first seen from there lives.
Eigen::Isometry3d AnchorAt(const Eigen::Vector3d& position) {
  Eigen::Isometry3d anchor = Eigen::Isometry3d::Identity();
  anchor.translation() = position;
  return anchor;
}

double TurnAngle(const Eigen::Isometry3d& motion) { return Eigen::AngleAxisd(motion.linear()).angle(); }

}  // namespace

LandmarkSlam::LandmarkSlam(const LandmarkSlamOptions& options, const Eigen::Isometry3d& vehicle_T_sensor)
    : options_(options), sensor_T_vehicle_(vehicle_T_sensor.inverse()) {
  graph_.vehicle_T_sensor = vehicle_T_sensor;
}

void LandmarkSlam::Add(TimeNs stamp, const Eigen::Isometry3d& odometry_world_T_vehicle,
                       const maps::features3d::FeatureSet& features, std::span<const Eigen::Vector3d> keypoints) {
  const auto start = std::chrono::steady_clock::now();
  ++stats_.revolutions;
  const bool new_node = AddPoseNodeIfKeyframe(odometry_world_T_vehicle);
  const int node = static_cast<int>(graph_.poses.size()) - 1;
  const Eigen::Isometry3d node_T_vehicle = last_node_odometry_.inverse() * odometry_world_T_vehicle;
  revolutions_.push_back(Revolution{stamp, node, node_T_vehicle});
  // Step 2: the revolution's features seen from the node's sensor frame.
  const Eigen::Isometry3d node_sensor_T_sensor = sensor_T_vehicle_ * node_T_vehicle * graph_.vehicle_T_sensor;
  for (const PlaneFeature& plane : features.planes) AddPlane(node, node_sensor_T_sensor, plane);
  for (const LineFeature& line : features.lines) AddLine(node, node_sensor_T_sensor, line);
  for (const Eigen::Vector3d& keypoint : keypoints) AddPoint(node, node_sensor_T_sensor, keypoint);
  if (new_node && ++nodes_since_optimization_ >= options_.optimize_every_nodes) {
    const int nodes = static_cast<int>(graph_.poses.size());
    Optimize(options_.iterations_per_optimization, options_.window_nodes > 0 ? std::max(nodes - options_.window_nodes, 1) : 1);
  }
  stats_.backend_ms_total += MillisecondsSince(start);
}

void LandmarkSlam::Finish() {
  const auto start = std::chrono::steady_clock::now();
  Optimize(options_.final_iterations, 1);
  stats_.backend_ms_total += MillisecondsSince(start);
}

bool LandmarkSlam::AddPoseNodeIfKeyframe(const Eigen::Isometry3d& odometry_world_T_vehicle) {
  if (graph_.poses.empty()) {
    graph_.poses.push_back(PoseNode{odometry_world_T_vehicle});
    last_node_odometry_ = odometry_world_T_vehicle;
    stats_.pose_nodes = 1;
    return true;
  }
  const Eigen::Isometry3d motion = last_node_odometry_.inverse() * odometry_world_T_vehicle;
  if (motion.translation().norm() < options_.keyframe_distance_m && TurnAngle(motion) < options_.keyframe_angle_rad) {
    return false;
  }
  const int from = static_cast<int>(graph_.poses.size()) - 1;
  graph_.odometry.push_back(OdometryFactor{from, motion, OdometryInformation(motion, options_.odometry)});
  graph_.poses.push_back(PoseNode{graph_.poses.back().world_T_vehicle * motion});
  last_node_odometry_ = odometry_world_T_vehicle;
  travel_m_ += motion.translation().norm();
  stats_.pose_nodes = static_cast<int>(graph_.poses.size());
  return true;
}

Eigen::Isometry3d LandmarkSlam::WorldTSensor(int node) const {
  return graph_.poses[static_cast<std::size_t>(node)].world_T_vehicle * graph_.vehicle_T_sensor;
}

void LandmarkSlam::AddPlane(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const PlaneFeature& feature) {
  const PlaneFeature in_node = TransformedFeature(node_sensor_T_sensor, feature);
  const std::optional<PlaneMeasurement> measurement = PlaneMeasurementOf(in_node, options_.floors);
  if (!measurement) {
    ++stats_.rejected_features;
    return;
  }
  const Eigen::Isometry3d world_T_sensor = WorldTSensor(node);
  const PlaneFeature in_world = TransformedFeature(world_T_sensor, in_node);
  const std::optional<int> match = AssociatePlane(plane_tracks_, in_world, options_.gates);
  int landmark = 0;
  if (match) {
    landmark = *match;
    ExtendTrack(in_world, plane_tracks_[static_cast<std::size_t>(landmark)]);
    ++stats_.associations;
  } else {
    landmark = static_cast<int>(graph_.planes.size());
    PlaneNode created;
    created.world_T_anchor = AnchorAt(world_T_sensor.translation());
    created.plane = Transformed(created.world_T_anchor.inverse(), Plane{in_world.normal, in_world.d});
    graph_.planes.push_back(created);
    plane_tracks_.push_back(StartPlaneTrack(in_world));
    ++stats_.new_landmarks;
    stats_.plane_landmarks = static_cast<int>(graph_.planes.size());
  }
  graph_.plane_observations.push_back(
      PlaneObservation{node, landmark, measurement->plane, measurement->information, in_node.centroid});
  ++graph_.planes[static_cast<std::size_t>(landmark)].observations;
  ++stats_.plane_factors;
}

void LandmarkSlam::AddLine(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const LineFeature& feature) {
  const LineFeature in_node = TransformedFeature(node_sensor_T_sensor, feature);
  const std::optional<LineMeasurement> measurement = LineMeasurementOf(in_node, options_.floors);
  if (!measurement) {
    ++stats_.rejected_features;
    return;
  }
  const Eigen::Isometry3d world_T_sensor = WorldTSensor(node);
  const LineFeature in_world = TransformedFeature(world_T_sensor, in_node);
  const std::optional<int> match = AssociateLine(line_tracks_, in_world, options_.gates, travel_m_);
  int landmark = 0;
  if (match) {
    landmark = *match;
    ExtendTrack(in_world, line_tracks_[static_cast<std::size_t>(landmark)]);
    line_tracks_[static_cast<std::size_t>(landmark)].last_seen_travel_m = travel_m_;
    ++stats_.associations;
  } else {
    landmark = static_cast<int>(graph_.lines.size());
    LineNode created;
    created.world_T_anchor = AnchorAt(world_T_sensor.translation());
    // The sensor saw the line from off it, so the anchor is off it too (line.hpp).
    created.line = ToOrthonormal(Transformed(created.world_T_anchor.inverse() * world_T_sensor, measurement->line));
    graph_.lines.push_back(created);
    AddLineTrack(StartLineTrack(in_world), travel_m_, options_.gates, line_tracks_);
    ++stats_.new_landmarks;
    stats_.line_landmarks = static_cast<int>(graph_.lines.size());
  }
  graph_.line_observations.push_back(
      LineObservation{node, landmark, measurement->line, measurement->information, in_node.point});
  ++graph_.lines[static_cast<std::size_t>(landmark)].observations;
  ++stats_.line_factors;
}

void LandmarkSlam::AddPoint(int node, const Eigen::Isometry3d& node_sensor_T_sensor, const Eigen::Vector3d& keypoint) {
  if (!keypoint.allFinite()) {
    ++stats_.rejected_features;
    return;
  }
  const Eigen::Vector3d in_node = node_sensor_T_sensor * keypoint;
  const Eigen::Isometry3d world_T_sensor = WorldTSensor(node);
  const Eigen::Vector3d in_world = world_T_sensor * in_node;
  const std::optional<int> match = AssociatePoint(point_tracks_, in_world, options_.gates);
  int landmark = 0;
  if (match) {
    landmark = *match;
    ++stats_.associations;
  } else {
    landmark = static_cast<int>(graph_.points.size());
    PointNode created;
    created.world_T_anchor = AnchorAt(world_T_sensor.translation());
    created.point = created.world_T_anchor.inverse() * in_world;
    graph_.points.push_back(created);
    point_tracks_.push_back(in_world);
    ++stats_.new_landmarks;
    stats_.point_landmarks = static_cast<int>(graph_.points.size());
  }
  graph_.point_observations.push_back(PointObservation{node, landmark, in_node, PointInformation(options_.point_sigma_m)});
  ++graph_.points[static_cast<std::size_t>(landmark)].observations;
  ++stats_.point_factors;
}

void LandmarkSlam::Optimize(int iterations, int first_free_pose) {
  const OptimizationResult result = OptimizeGraph(graph_, options_.optimizer, iterations, first_free_pose);
  ++stats_.optimizations;
  stats_.iterations += result.iterations;
  stats_.downweighted_factors = result.downweighted_factors;
  stats_.final_cost = result.final_cost;
  stats_.solve_ms_total += result.milliseconds;
  stats_.last_solve_ms = result.milliseconds;
  nodes_since_optimization_ = 0;
  RefreshTracks();
}

// Association predicts against the optimized landmarks; the extents stay as they were.
void LandmarkSlam::RefreshTracks() {
  for (std::size_t l = 0; l < graph_.planes.size(); ++l) {
    const Plane world = Transformed(graph_.planes[l].world_T_anchor, graph_.planes[l].plane);
    plane_tracks_[l].plane = world;
  }
  for (std::size_t l = 0; l < graph_.lines.size(); ++l) {
    const std::optional<PluckerLine> anchored = ToPlucker(graph_.lines[l].line);
    if (!anchored) continue;
    const PluckerLine world = Transformed(graph_.lines[l].world_T_anchor, *anchored);
    LineTrack& track = line_tracks_[l];
    const Eigen::Vector3d direction = Direction(world);
    track.direction = direction.dot(track.direction) < 0.0 ? Eigen::Vector3d(-direction) : direction;
    const Eigen::Vector3d nearest_origin = ClosestPointToOrigin(world);
    track.point = nearest_origin + (track.point - nearest_origin).dot(track.direction) * track.direction;
  }
  for (std::size_t l = 0; l < graph_.points.size(); ++l) point_tracks_[l] = graph_.points[l].world_T_anchor * graph_.points[l].point;
}

std::vector<hal::trajectory::StampedPose> LandmarkSlam::Trajectory() const {
  std::vector<hal::trajectory::StampedPose> trajectory;
  trajectory.reserve(revolutions_.size());
  for (const Revolution& r : revolutions_) {
    trajectory.push_back({r.stamp, graph_.poses[static_cast<std::size_t>(r.node)].world_T_vehicle * r.node_T_vehicle});
  }
  return trajectory;
}

std::vector<LandmarkSlam::PlaneLandmark> LandmarkSlam::Planes() const {
  std::vector<PlaneLandmark> planes(graph_.planes.size());
  std::vector<Eigen::Vector3d> sum(graph_.planes.size(), Eigen::Vector3d::Zero());
  for (const PlaneObservation& o : graph_.plane_observations) sum[static_cast<std::size_t>(o.landmark)] += WorldTSensor(o.pose) * o.centroid;
  for (std::size_t l = 0; l < planes.size(); ++l) {
    const PlaneNode& node = graph_.planes[l];
    planes[l].plane = Transformed(node.world_T_anchor, node.plane);
    planes[l].observations = node.observations;
    const Eigen::Vector3d mean = sum[l] / static_cast<double>(std::max(node.observations, 1));
    const Eigen::Vector3d& n = planes[l].plane.normal;
    planes[l].centroid = mean - (n.dot(mean) + planes[l].plane.distance) * n;
  }
  return planes;
}

std::vector<LandmarkSlam::LineLandmark> LandmarkSlam::Lines() const {
  std::vector<LineLandmark> lines(graph_.lines.size());
  std::vector<Eigen::Vector3d> sum(graph_.lines.size(), Eigen::Vector3d::Zero());
  for (const LineObservation& o : graph_.line_observations) sum[static_cast<std::size_t>(o.landmark)] += WorldTSensor(o.pose) * o.point;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const LineNode& node = graph_.lines[l];
    lines[l].observations = node.observations;
    // The track's direction: a landmark at infinity (never in practice) keeps its last finite state.
    lines[l].direction = line_tracks_[l].direction;
    Eigen::Vector3d on_line = line_tracks_[l].point;
    if (const std::optional<PluckerLine> anchored = ToPlucker(node.line)) {
      const PluckerLine world = Transformed(node.world_T_anchor, *anchored);
      lines[l].direction = Direction(world);
      on_line = ClosestPointToOrigin(world);
    }
    const Eigen::Vector3d mean = sum[l] / static_cast<double>(std::max(node.observations, 1));
    const Eigen::Vector3d& d = lines[l].direction;
    lines[l].point = on_line + (mean - on_line).dot(d) * d;
  }
  return lines;
}

std::vector<LandmarkSlam::PointLandmark> LandmarkSlam::Points() const {
  std::vector<PointLandmark> points(graph_.points.size());
  for (std::size_t l = 0; l < points.size(); ++l) {
    points[l].position = graph_.points[l].world_T_anchor * graph_.points[l].point;
    points[l].observations = graph_.points[l].observations;
  }
  return points;
}

}  // namespace flat2d::localization::landmarks
