#include "localization/evaluation/feature_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hal/common/angles.hpp"

namespace flat2d::localization::evaluation {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kRadToDeg;
}

// Where a world point lies against a face: across (along the outward normal), along the
// footprint from a, and whether its height is within the face's (+ margin).
struct FaceCoordinates {
  double across, along, length;
  bool within_height;
};
FaceCoordinates OnFace(const hal::sim::TruthFace& face, const Eigen::Vector3d& p, double margin) {
  const Eigen::Vector2d edge = face.b - face.a;
  const double length = edge.norm();
  const Eigen::Vector2d offset = p.head<2>() - face.a;
  return {face.outward.dot(offset), offset.dot(edge) / length, length,
          p.z() >= face.z_bottom - margin && p.z() <= face.z_top + margin};
}

bool Within(const FaceCoordinates& c, double margin) {
  return c.within_height && c.along >= -margin && c.along <= c.length + margin;
}

double AxisDistance(const hal::sim::TruthPole& pole, const Eigen::Vector3d& p) { return (p.head<2>() - pole.center).norm(); }

// Whether a pole stands within its radius of a face's footprint (pillars built into walls).
bool EmbeddedInAFace(const hal::sim::TruthPole& pole, const hal::sim::SceneLandmarks& truth) {
  const Eigen::Vector3d axis(pole.center.x(), pole.center.y(), 0.5 * (pole.z_bottom + pole.z_top));
  return std::any_of(truth.faces.begin(), truth.faces.end(), [&](const hal::sim::TruthFace& f) {
    const FaceCoordinates c = OnFace(f, axis, 0.0);
    return std::abs(c.across) < pole.radius && c.along > 0.0 && c.along < c.length;
  });
}

// The points seen on a face or pole: how many, and how far they spread (along a face's
// footprint, up a pole).
struct Seen {
  int count = 0;
  double low = 0.0, high = 0.0;
  void Add(double coordinate) {
    low = count == 0 ? coordinate : std::min(low, coordinate);
    high = count == 0 ? coordinate : std::max(high, coordinate);
    ++count;
  }
  bool InView(int min_points, double min_spread) const { return count >= min_points && high - low >= min_spread; }
};

// Counts, per face and pole, the revolution's points on its visible surface.
void CountInView(const std::vector<Eigen::Vector3f>& sensor_points, const Eigen::Isometry3d& world_T_sensor,
                 const hal::sim::SceneLandmarks& truth, const FeatureAccuracyOptions& options, RevolutionAccuracy& out) {
  const Eigen::Vector3d sensor = world_T_sensor.translation();
  const double reach = options.max_range_m + options.on_surface_m;
  std::vector<int> near_faces, near_poles;  // those the points can reach, facing the sensor
  for (std::size_t k = 0; k < truth.faces.size(); ++k) {
    const hal::sim::TruthFace& f = truth.faces[k];
    if ((f.b - f.a).norm() < options.min_face_width_m) continue;  // an edge: no plane expected
    const FaceCoordinates c = OnFace(f, sensor, 0.0);
    const double gap = std::max({0.0, -c.along, c.along - c.length});
    if (c.across > 0.0 && std::hypot(c.across, gap) < reach) near_faces.push_back(static_cast<int>(k));
  }
  for (std::size_t k = 0; k < truth.poles.size(); ++k) {
    if (EmbeddedInAFace(truth.poles[k], truth)) continue;  // a bump on a wall, no line of its own
    if (AxisDistance(truth.poles[k], sensor) < reach + truth.poles[k].radius) near_poles.push_back(static_cast<int>(k));
  }
  std::vector<Seen> face_hits(near_faces.size()), pole_hits(near_poles.size());
  for (const Eigen::Vector3f& q : sensor_points) {
    if (q.cast<double>().norm() > options.max_range_m) continue;
    const Eigen::Vector3d p = world_T_sensor * q.cast<double>();
    for (std::size_t i = 0; i < near_faces.size(); ++i) {
      const FaceCoordinates c = OnFace(truth.faces[static_cast<std::size_t>(near_faces[i])], p, options.on_surface_m);
      if (std::abs(c.across) < options.on_surface_m && Within(c, options.on_surface_m)) face_hits[i].Add(c.along);
    }
    for (std::size_t i = 0; i < near_poles.size(); ++i) {
      const hal::sim::TruthPole& pole = truth.poles[static_cast<std::size_t>(near_poles[i])];
      if (std::abs(AxisDistance(pole, p) - pole.radius) < options.on_surface_m && p.z() >= pole.z_bottom &&
          p.z() <= pole.z_top) {
        pole_hits[i].Add(p.z());
      }
    }
  }
  for (std::size_t i = 0; i < near_faces.size(); ++i) {
    if (face_hits[i].InView(options.in_view_points, options.in_view_width_m)) out.faces_in_view.push_back(near_faces[i]);
  }
  for (std::size_t i = 0; i < near_poles.size(); ++i) {
    if (pole_hits[i].InView(options.in_view_points, options.in_view_height_m)) out.poles_in_view.push_back(near_poles[i]);
  }
}

bool OnMover(const Eigen::Vector3d& p, const std::vector<hal::sim::MoverFootprint>& movers, double margin) {
  return std::any_of(movers.begin(), movers.end(), [&](const hal::sim::MoverFootprint& m) {
    return (p.head<2>() - m.center).norm() < m.radius + margin;
  });
}

// Half the horizontal width of a plane feature: its extent along the horizontal direction
// within it.
double HalfWidth(const maps::features3d::PlaneFeature& plane) {
  const Eigen::Vector3d horizontal = Eigen::Vector3d::UnitZ().cross(plane.normal).normalized();
  const Eigen::Vector3d minor_axis = plane.normal.cross(plane.major_axis);
  return plane.half_extent.x() * std::abs(plane.major_axis.dot(horizontal)) +
         plane.half_extent.y() * std::abs(minor_axis.dot(horizontal));
}

// A plane matches the face nearest its centroid (errors from that one), and finds every face
// of the same wall its extent covers: a wall with doors is several faces in one plane.
void MatchPlane(const maps::features3d::PlaneFeature& plane, const Eigen::Isometry3d& world_T_sensor,
                const hal::sim::SceneLandmarks& truth, const FeatureAccuracyOptions& options, RevolutionAccuracy& out) {
  const Eigen::Vector3d normal = world_T_sensor.linear() * plane.normal;
  const Eigen::Vector3d centroid = world_T_sensor * plane.centroid;
  const double half_width = HalfWidth(plane);
  std::optional<std::size_t> best;
  double best_offset = options.offset_gate_m;
  for (std::size_t k = 0; k < truth.faces.size(); ++k) {
    const hal::sim::TruthFace& f = truth.faces[k];
    if ((f.b - f.a).norm() < options.min_face_width_m) continue;
    const Eigen::Vector3d outward(f.outward.x(), f.outward.y(), 0.0);
    if (AngleDeg(normal, outward) > options.normal_gate_deg) continue;
    const FaceCoordinates c = OnFace(f, centroid, options.extent_margin_m);
    if (!(std::abs(c.across) < options.offset_gate_m) || !c.within_height) continue;
    if (c.along + half_width < 0.0 || c.along - half_width > c.length) continue;  // no overlap
    out.faces_found.push_back(static_cast<int>(k));
    if (std::abs(c.across) < best_offset && Within(c, options.extent_margin_m)) {
      best_offset = std::abs(c.across);
      best = k;
    }
  }
  if (!best) return;
  const hal::sim::TruthFace& f = truth.faces[*best];
  const Eigen::Vector3d truth_normal = world_T_sensor.linear().transpose() * Eigen::Vector3d(f.outward.x(), f.outward.y(), 0.0);
  const Eigen::Vector3d truth_point = world_T_sensor.inverse() * Eigen::Vector3d(f.a.x(), f.a.y(), f.z_bottom);
  ++out.planes_matched;
  out.normal_error_deg.push_back(AngleDeg(plane.normal, truth_normal));
  out.offset_error_m.push_back(std::abs(plane.d + truth_normal.dot(truth_point)));  // d_truth = -n.p
}

// Whether a world point is on a vertical edge: near the middle of a narrow face.
bool OnEdge(const Eigen::Vector3d& p, const hal::sim::SceneLandmarks& truth, const FeatureAccuracyOptions& options) {
  return std::any_of(truth.faces.begin(), truth.faces.end(), [&](const hal::sim::TruthFace& f) {
    const double width = (f.b - f.a).norm();
    if (width >= options.min_face_width_m) return false;
    if (p.z() < f.z_bottom - options.extent_margin_m || p.z() > f.z_top + options.extent_margin_m) return false;
    return (p.head<2>() - 0.5 * (f.a + f.b)).norm() < 0.5 * width + options.axis_gate_m;
  });
}

void MatchLine(const maps::features3d::LineFeature& line, const Eigen::Isometry3d& world_T_sensor,
               const hal::sim::SceneLandmarks& truth, const FeatureAccuracyOptions& options, RevolutionAccuracy& out) {
  const Eigen::Vector3d centroid = world_T_sensor * line.point;
  std::optional<std::size_t> best;
  double best_distance = 0.0;
  for (std::size_t k = 0; k < truth.poles.size(); ++k) {
    const hal::sim::TruthPole& pole = truth.poles[k];
    const double distance = AxisDistance(pole, centroid);
    if (distance > pole.radius + options.axis_gate_m) continue;
    if (centroid.z() < pole.z_bottom - options.extent_margin_m || centroid.z() > pole.z_top + options.extent_margin_m) continue;
    if (!best || distance < best_distance) {
      best = k;
      best_distance = distance;
    }
  }
  const Eigen::Vector3d direction = world_T_sensor.linear() * line.direction;
  if (!best) {
    if (!OnEdge(centroid, truth, options)) return;
    ++out.lines_matched;
    ++out.lines_on_edges;
    out.direction_error_deg.push_back(std::acos(std::min(1.0, std::abs(direction.z()))) * kRadToDeg);
    return;
  }
  ++out.lines_matched;
  out.poles_found.push_back(static_cast<int>(*best));
  out.direction_error_deg.push_back(std::acos(std::min(1.0, std::abs(direction.z()))) * kRadToDeg);
  out.axis_distance_m.push_back(best_distance);
  if (best_distance <= truth.poles[*best].radius + 0.05) ++out.lines_near_axis;  // the bound
}

}  // namespace

RevolutionAccuracy EvaluateFeatures(const maps::features3d::FeatureSet& features,
                                    const std::vector<Eigen::Vector3f>& sensor_points,
                                    const Eigen::Isometry3d& world_T_sensor, const hal::sim::SceneLandmarks& truth,
                                    const std::vector<hal::sim::MoverFootprint>& movers,
                                    const FeatureAccuracyOptions& options) {
  RevolutionAccuracy out;
  CountInView(sensor_points, world_T_sensor, truth, options, out);
  auto counted = [&](const Eigen::Vector3d& sensor_centroid) {
    if (sensor_centroid.norm() > options.max_range_m) return false;
    if (!OnMover(world_T_sensor * sensor_centroid, movers, options.mover_margin_m)) return true;
    ++out.on_movers;
    return false;
  };
  for (const maps::features3d::PlaneFeature& plane : features.planes) {
    if (!counted(plane.centroid)) continue;
    ++out.planes;
    MatchPlane(plane, world_T_sensor, truth, options, out);
  }
  for (const maps::features3d::LineFeature& line : features.lines) {
    if (!counted(line.point)) continue;
    ++out.lines;
    MatchLine(line, world_T_sensor, truth, options, out);
  }
  return out;
}

}  // namespace flat2d::localization::evaluation
