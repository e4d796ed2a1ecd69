// MapBuilder: loop closures (see map_builder.hpp, step (4) of AddScan).
#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "localization/mapping/map_builder.hpp"

namespace flat2d::localization::mapping {
namespace {

// The variance along the least certain direction of a 2 x 2 covariance.
double LargestVariance(const Eigen::Matrix2d& c) {
  const double mean = 0.5 * (c(0, 0) + c(1, 1));
  const double half_difference = 0.5 * (c(0, 0) - c(1, 1));
  return mean + std::sqrt(half_difference * half_difference + c(0, 1) * c(1, 0));
}

// How sure the graph is of a relative pose along one axis: three standard deviations,
// within the bounds.
double SearchHalfWidth(double variance, double at_least, double at_most) {
  return std::clamp(3.0 * std::sqrt(std::max(variance, 0.0)), at_least, std::max(at_least, at_most));
}

}  // namespace

std::vector<MapBuilder::LoopCandidate> MapBuilder::NearbyKeyframes() const {
  const std::size_t k = keyframes_.size() - 1;
  const Keyframe& current = keyframes_[k];
  // Walking back along the chain of steps, the covariance of keyframe k relative to
  // keyframe j grows by each step's covariance carried into k's frame (first order): how
  // far the running estimate may have drifted between them (earlier loops ignored, so it
  // errs wide).
  std::vector<LoopCandidate> near;
  Eigen::Matrix3d chain = Eigen::Matrix3d::Zero();
  for (std::size_t j = k; j-- > 0;) {
    const Se2 rest = keyframes_[j + 1].estimate.Inverse() * current.estimate;  // j + 1 to k
    Eigen::Matrix3d carry = Eigen::Matrix3d::Identity();
    const Eigen::Matrix2d r_t = rest.Rotation().transpose();
    carry.topLeftCorner<2, 2>() = r_t;
    carry.topRightCorner<2, 1>() = r_t * Eigen::Vector2d(-rest.translation().y(), rest.translation().x());
    chain += carry * step_covariance_[j + 1] * carry.transpose();
    if (current.path_m - keyframes_[j].path_m < options_.loop_min_path_m) continue;
    const double spread = 3.0 * std::sqrt(std::max(LargestVariance(chain.topLeftCorner<2, 2>()), 0.0));
    const double radius =
        std::min(options_.loop_radius_m + spread, std::max(options_.loop_radius_m, options_.loop_max_radius_m));
    const double d = (keyframes_[j].estimate.translation() - current.estimate.translation()).norm();
    if (d <= radius) near.push_back({d, j, chain});
  }
  std::sort(near.begin(), near.end(),
            [](const LoopCandidate& a, const LoopCandidate& b) { return a.distance_m < b.distance_m; });
  return near;
}

void MapBuilder::CloseLoops() {
  const std::vector<LoopCandidate> near = NearbyKeyframes();
  // The nearest candidates, at least 2 submap widths apart so each tries another place.
  std::vector<const LoopCandidate*> chosen;
  for (const LoopCandidate& candidate : near) {
    if (static_cast<int>(chosen.size()) >= options_.loop_candidates) break;
    const bool distinct = std::all_of(chosen.begin(), chosen.end(), [&](const LoopCandidate* c) {
      return std::abs(static_cast<long>(c->keyframe) - static_cast<long>(candidate.keyframe)) >
             2 * options_.loop_submap_keyframes;
    });
    if (distinct) chosen.push_back(&candidate);
  }
  for (const LoopCandidate* candidate : chosen) TryLoop(candidate->keyframe, candidate->chain_covariance);
}

void MapBuilder::TryLoop(std::size_t j, const Eigen::Matrix3d& chain_covariance) {
  const std::size_t k = keyframes_.size() - 1;
  const Keyframe& current = keyframes_[k];
  ++stats_.loop_candidates;
  const auto side = static_cast<std::size_t>(options_.loop_submap_keyframes);
  const std::size_t first = j > side ? j - side : 0;
  std::size_t last = std::min(j + side, k - 1);
  // The submap must not reach the keyframes the current one was just tracked against.
  while (last > j && current.path_m - keyframes_[last].path_m < options_.loop_min_path_m) --last;
  const SearchWindow window{
      SearchHalfWidth(LargestVariance(chain_covariance.topLeftCorner<2, 2>()),
                      options_.loop_window.linear, options_.loop_max_window.linear),
      SearchHalfWidth(chain_covariance(2, 2), options_.loop_window.angular, options_.loop_max_window.angular)};
  const MatchResult match = MatchAgainst(k, first, last, current.estimate, window);
  if (!match.ok() || match.score < options_.loop_min_score) return;
  const Se2 measurement = keyframes_[j].estimate.Inverse() * match.map_T_vehicle;
  const Eigen::Matrix3d information = MatchInformation(match);
  const Eigen::Vector3d error = graph::BetweenError(keyframes_[j].estimate, current.estimate, measurement);
  const Eigen::Matrix3d innovation = information.inverse() + chain_covariance;
  if (error.dot(innovation.ldlt().solve(error)) > options_.loop_gate_chi2) {
    ++stats_.loop_gated;
    return;
  }
  ++stats_.loop_accepted;
  ++loops_since_optimization_;
  graph_.mixture_betweens.push_back({j, k, measurement,
                                     graph::MakeNullHypothesisMixture(information, options_.loop_null_weight,
                                                                      options_.loop_null_scale)});
  // Farther from the estimate than the match's own spread: the null hypothesis would win
  // before the graph had a chance to move. The graph allows it (the gate above), so it is
  // closed at once, as a plain Gaussian first.
  if (graph::SelectMixtureComponent(graph_.mixture_betweens.back().mixture, error).component != 0) {
    drift_loops_.push_back(graph_.mixture_betweens.size() - 1);
    ++stats_.loop_drift_closed;
    loops_since_optimization_ = std::max(loops_since_optimization_, options_.optimize_every);
  }
}

}  // namespace flat2d::localization::mapping
