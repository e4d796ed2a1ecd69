#include "localization/evaluation/trajectory_error_3d.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hal/common/angles.hpp"
#include "hal/trajectory/pose_interpolation.hpp"
#include "localization/evaluation/trajectory_error.hpp"

namespace flat2d::localization::evaluation {
namespace {

using hal::trajectory::StampedPose;

// Times within this of a pose are that pose, as relations.hpp's PoseAt: files print 6 decimals.
constexpr TimeNs kSameTimeNs = 2 * kNsPerUs;

TimeNs SecondsToNs(double seconds) { return static_cast<TimeNs>(std::llround(seconds * 1e9)); }

// The truth at each estimate pose, nullopt where it has none (step 1).
std::vector<std::optional<Eigen::Isometry3d>> TruthAtEstimate(const std::vector<StampedPose>& estimate,
                                                              const std::vector<StampedPose>& truth,
                                                              TimeNs max_gap_ns) {
  std::vector<std::optional<Eigen::Isometry3d>> out;
  out.reserve(estimate.size());
  for (const StampedPose& p : estimate) out.push_back(InterpolatedPose(truth, p.time_ns, max_gap_ns));
  return out;
}

struct AbsoluteError {
  Eigen::Isometry3d truth_T_estimate = Eigen::Isometry3d::Identity();
  std::vector<double> distances_m;
};

// Step 2: Umeyama's closed form without scale (the SVD form of Horn's method), then the
// distances after it.
AbsoluteError Absolute(const std::vector<StampedPose>& estimate,
                       const std::vector<std::optional<Eigen::Isometry3d>>& truth) {
  std::vector<std::size_t> matched;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i]) matched.push_back(i);
  }
  Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(matched.size())), to(3, from.cols());
  for (std::size_t k = 0; k < matched.size(); ++k) {
    from.col(static_cast<Eigen::Index>(k)) = estimate[matched[k]].world_T_body.translation();
    to.col(static_cast<Eigen::Index>(k)) = truth[matched[k]]->translation();
  }
  AbsoluteError out;
  out.truth_T_estimate.matrix() = Eigen::umeyama(from, to, /*with_scaling=*/false);
  out.distances_m.reserve(matched.size());
  for (Eigen::Index k = 0; k < from.cols(); ++k) {
    out.distances_m.push_back((out.truth_T_estimate * Eigen::Vector3d(from.col(k)) - to.col(k)).norm());
  }
  return out;
}

// The estimate pose paired with pose i (step 3): i + 1 per frame, else the first pose at
// least `delta_ns` after i; estimate.size() where there is none.
std::size_t Partner(const std::vector<StampedPose>& estimate, std::size_t i, std::optional<TimeNs> delta_ns) {
  if (!delta_ns) return i + 1;
  const TimeNs target = estimate[i].time_ns + *delta_ns;
  const auto j = std::lower_bound(estimate.begin() + static_cast<std::ptrdiff_t>(i) + 1, estimate.end(), target,
                                  [](const StampedPose& p, TimeNs t) { return p.time_ns < t; });
  return static_cast<std::size_t>(j - estimate.begin());
}

double Rms(const std::vector<double>& values) {
  double squares = 0.0;
  for (const double v : values) squares += v * v;
  return values.empty() ? 0.0 : std::sqrt(squares / static_cast<double>(values.size()));
}

// Eq. 1 over every pair the truth covers at both ends; Eq. 2 and the medians of the norms.
RelativeError3d Relative(const std::vector<StampedPose>& estimate,
                         const std::vector<std::optional<Eigen::Isometry3d>>& truth, std::optional<TimeNs> delta_ns) {
  std::vector<double> translation_m, rotation_deg;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const std::size_t j = Partner(estimate, i, delta_ns);
    if (j >= estimate.size() || !truth[i] || !truth[j]) continue;
    const Eigen::Isometry3d truth_motion = truth[i]->inverse() * *truth[j];
    const Eigen::Isometry3d estimate_motion = estimate[i].world_T_body.inverse() * estimate[j].world_T_body;
    const Eigen::Isometry3d error = truth_motion.inverse() * estimate_motion;
    translation_m.push_back(error.translation().norm());
    rotation_deg.push_back(Eigen::AngleAxisd(error.linear()).angle() * kRadToDeg);
  }
  RelativeError3d out;
  out.pairs = translation_m.size();
  out.trans_rmse_m = Rms(translation_m);
  out.rot_rmse_deg = Rms(rotation_deg);
  out.trans_median_m = PercentilesOf(std::move(translation_m)).p50;
  out.rot_median_deg = PercentilesOf(std::move(rotation_deg)).p50;
  return out;
}

}  // namespace

std::optional<Eigen::Isometry3d> InterpolatedPose(const std::vector<StampedPose>& trajectory, TimeNs time_ns,
                                                  TimeNs max_gap_ns) {
  const auto after = std::lower_bound(trajectory.begin(), trajectory.end(), time_ns - kSameTimeNs,
                                      [](const StampedPose& p, TimeNs t) { return p.time_ns < t; });
  if (after != trajectory.end() && std::abs(after->time_ns - time_ns) <= kSameTimeNs) return after->world_T_body;
  if (after == trajectory.begin() || after == trajectory.end()) return std::nullopt;
  const StampedPose& before = *(after - 1);
  const TimeNs gap = after->time_ns - before.time_ns;
  if (gap > max_gap_ns) return std::nullopt;
  const double fraction = static_cast<double>(time_ns - before.time_ns) / static_cast<double>(gap);
  return hal::trajectory::InterpolatePose(before.world_T_body, after->world_T_body, fraction);
}

Result<TrajectoryError3d> EvaluateTrajectory3d(const std::vector<StampedPose>& estimate,
                                               const std::vector<StampedPose>& truth,
                                               const TrajectoryError3dOptions& options) {
  const auto truth_at = TruthAtEstimate(estimate, truth, SecondsToNs(options.max_gap_s));
  TrajectoryError3d out;
  out.poses_matched = static_cast<std::size_t>(std::count_if(truth_at.begin(), truth_at.end(),
                                                             [](const auto& q) { return q.has_value(); }));
  out.poses_unmatched = estimate.size() - out.poses_matched;
  if (out.poses_matched == 0) {
    return MakeError("the truth covers none of the estimate's " + std::to_string(estimate.size()) +
                     " poses (truth poses around each at most " + std::to_string(options.max_gap_s) + " s apart)");
  }
  AbsoluteError absolute = Absolute(estimate, truth_at);
  out.truth_T_estimate = absolute.truth_T_estimate;
  out.ate_rmse_m = Rms(absolute.distances_m);
  double sum = 0.0;
  for (const double d : absolute.distances_m) {
    sum += d;
    out.ate_max_m = std::max(out.ate_max_m, d);
  }
  out.ate_mean_m = sum / static_cast<double>(out.poses_matched);
  out.ate_median_m = PercentilesOf(std::move(absolute.distances_m)).p50;
  out.rpe_frame = Relative(estimate, truth_at, std::nullopt);
  out.rpe_delta_s = options.rpe_delta_s;
  out.rpe_delta = Relative(estimate, truth_at, SecondsToNs(options.rpe_delta_s));
  return out;
}

}  // namespace flat2d::localization::evaluation
