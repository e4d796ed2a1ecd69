#include "localization/evaluation/trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flat2d::localization::evaluation {

TrajectoryError EvaluateTrajectory(const std::vector<TimedPose>& estimate, const std::vector<TimedPose>& reference,
                                   bool align, double max_gap_s) {
  TrajectoryError out;
  std::vector<Se2> est, ref;
  for (const TimedPose& r : reference) {
    Se2 pose;
    if (PoseAt(estimate, r.time_s, max_gap_s, pose)) {
      est.push_back(pose);
      ref.push_back(r.pose);
    } else {
      ++out.unmatched;
    }
  }
  out.poses = est.size();
  if (est.empty()) return out;

  if (align) {
    Eigen::Vector2d mean_est = Eigen::Vector2d::Zero(), mean_ref = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < est.size(); ++i) {
      mean_est += est[i].translation();
      mean_ref += ref[i].translation();
    }
    mean_est /= static_cast<double>(est.size());
    mean_ref /= static_cast<double>(est.size());
    // The rotation maximizing sum ref_i . R est_i over centred points: atan2 of the
    // summed cross and dot products.
    double dot = 0.0, cross = 0.0;
    for (std::size_t i = 0; i < est.size(); ++i) {
      const Eigen::Vector2d a = est[i].translation() - mean_est;
      const Eigen::Vector2d b = ref[i].translation() - mean_ref;
      dot += a.dot(b);
      cross += a.x() * b.y() - a.y() * b.x();
    }
    const double angle = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
    const Se2 rotation(0.0, 0.0, angle);
    out.reference_T_estimate = Se2(mean_ref - rotation.Rotation() * mean_est, angle);
  }

  std::vector<double> distances;
  double squares = 0.0, sum = 0.0, rotation_squares = 0.0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Se2 aligned = out.reference_T_estimate * est[i];
    const double d = (aligned.translation() - ref[i].translation()).norm();
    const double dtheta = NormalizeAngle(aligned.theta() - ref[i].theta()) * 180.0 / std::numbers::pi;
    distances.push_back(d);
    squares += d * d;
    sum += d;
    rotation_squares += dtheta * dtheta;
    out.max_m = std::max(out.max_m, d);
  }
  const auto n = static_cast<double>(est.size());
  out.rmse_m = std::sqrt(squares / n);
  out.mean_m = sum / n;
  out.rotation_rmse_deg = std::sqrt(rotation_squares / n);
  std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2),
                   distances.end());
  out.median_m = distances[distances.size() / 2];
  return out;
}

}  // namespace flat2d::localization::evaluation
