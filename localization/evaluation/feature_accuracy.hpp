// 3D line and plane features of one revolution judged against the simulator's truth
// (issue 13's acceptance for thesis 8.1): which detections are landmarks of the world,
// which landmarks in view were found, and how far the found parameters are from the truth.
//
// A face or pole is "in view" when at least in_view_points of the revolution's points within
// max_range_m lie on it (within on_surface_m, on its visible side), spread over at least
// in_view_width_m along a face or in_view_height_m up a pole: a wall glimpsed through a
// door or a pole's foot behind a car is not a landmark anyone could fit. A plane matches a face
// whose outward normal is within normal_gate_deg of its own and whose plane passes within
// offset_gate_m of its centroid, the centroid inside the face's extent (+ margin), and it
// finds every such face its horizontal extent overlaps (a wall with doors is several faces
// in one plane); a line matches a pole whose axis passes within radius + axis_gate_m of its centroid. Poles built
// into a wall (the axis within the radius of a face) are bumps on it, never in view. Errors: a
// plane's normal angle and the difference of its offset d from the truth's in the sensor
// frame; a line's angle to the vertical and its centroid's distance from the axis.
// Faces narrower than min_face_width_m (wall ends at doors, thin boxes) are vertical edges,
// not planes: a line may match one (within half its width + axis_gate_m of its middle), and
// no plane is expected of them. Detections near a moving object are set aside (the truth has
// no landmark there).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "hal/sim/scene_landmarks.hpp"
#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::localization::evaluation {

struct FeatureAccuracyOptions {
  double max_range_m = 20.0;     // the "in view within 20 m"
  int in_view_points = 20;
  double in_view_width_m = 1.0;
  double in_view_height_m = 1.0;
  double on_surface_m = 0.05;
  double normal_gate_deg = 10.0;
  double offset_gate_m = 0.3;
  double extent_margin_m = 0.5;
  double axis_gate_m = 0.3;
  double min_face_width_m = 0.6;
  double mover_margin_m = 1.0;
};

struct RevolutionAccuracy {
  // Detections with centroids within max_range_m, not on movers, and those matched.
  int planes = 0, planes_matched = 0;
  int lines = 0, lines_matched = 0;  // matched: to a pole or a vertical edge
  int lines_on_edges = 0;
  int lines_near_axis = 0;  // matched to a pole within its radius + 5 cm of the axis
  int on_movers = 0;
  // Indices into SceneLandmarks::faces / poles: in view, and found by a matched detection.
  std::vector<int> faces_in_view, faces_found, poles_in_view, poles_found;
  std::vector<double> normal_error_deg, offset_error_m;     // per matched plane
  std::vector<double> direction_error_deg, axis_distance_m;  // per matched line
};

RevolutionAccuracy EvaluateFeatures(const maps::features3d::FeatureSet& features,
                                    const std::vector<Eigen::Vector3f>& sensor_points,
                                    const Eigen::Isometry3d& world_T_sensor, const hal::sim::SceneLandmarks& truth,
                                    const std::vector<hal::sim::MoverFootprint>& movers,
                                    const FeatureAccuracyOptions& options);

}  // namespace flat2d::localization::evaluation
