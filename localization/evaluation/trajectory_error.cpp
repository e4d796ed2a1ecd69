#include "localization/evaluation/trajectory_error.hpp"

#include <algorithm>
#include <cmath>

#include "hal/common/angles.hpp"

namespace flat2d::localization::evaluation {

ErrorPercentiles PercentilesOf(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  const auto rank = [&](double p) {
    const auto index = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(index, 1, values.size()) - 1];
  };
  return {rank(0.50), rank(0.95), rank(0.99)};
}

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

  std::vector<double> distances, longitudinal, lateral;
  double squares = 0.0, sum = 0.0, rotation_squares = 0.0;
  std::size_t within_0_02 = 0, within_0_025 = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Se2 aligned = out.reference_T_estimate * est[i];
    const Eigen::Vector2d difference = aligned.translation() - ref[i].translation();
    const Eigen::Vector2d in_reference = ref[i].Rotation().transpose() * difference;
    const double d = difference.norm();
    const double heading_error = std::abs(NormalizeAngle(aligned.theta() - ref[i].theta()));
    const double dtheta = heading_error * kRadToDeg;
    distances.push_back(d);
    longitudinal.push_back(std::abs(in_reference.x()));
    lateral.push_back(std::abs(in_reference.y()));
    squares += d * d;
    sum += d;
    rotation_squares += dtheta * dtheta;
    out.max_m = std::max(out.max_m, d);
    out.heading_worst_rad = std::max(out.heading_worst_rad, heading_error);
    within_0_02 += heading_error <= 0.02 ? 1 : 0;
    within_0_025 += heading_error <= 0.025 ? 1 : 0;
    ++out.heading_histogram[std::min(kHeadingBins - 1, static_cast<std::size_t>(heading_error / kHeadingBinRad))];
  }
  const auto n = static_cast<double>(est.size());
  out.rmse_m = std::sqrt(squares / n);
  out.mean_m = sum / n;
  out.rotation_rmse_deg = std::sqrt(rotation_squares / n);
  out.heading_within_0_02 = static_cast<double>(within_0_02) / n;
  out.heading_within_0_025 = static_cast<double>(within_0_025) / n;
  out.position_m = PercentilesOf(distances);
  out.longitudinal_m = PercentilesOf(std::move(longitudinal));
  out.lateral_m = PercentilesOf(std::move(lateral));
  std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2),
                   distances.end());
  out.median_m = distances[distances.size() / 2];
  return out;
}

}  // namespace flat2d::localization::evaluation
