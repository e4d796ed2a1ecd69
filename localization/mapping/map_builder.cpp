#include "localization/mapping/map_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "localization/graph/graph_optimizer.hpp"

namespace flat2d::localization::mapping {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

MatcherLimits LimitsFor(const MapBuilderOptions& options) {
  MatcherLimits limits;
  limits.max_points = 4000;
  const double widest = std::max({options.loop_window.linear, options.loop_max_window.linear,
                                  options.tracking_window.linear, options.refine_window.linear});
  const double side = 2.0 * (options.point_range_m + widest) + 2.0;
  const auto cells = static_cast<std::size_t>(std::ceil(side / options.match_resolution_m));
  limits.max_map_cells = cells * cells;
  limits.max_window_cells = static_cast<int>(std::ceil(widest / options.match_resolution_m)) + 2;
  limits.max_headings = 1024;
  return limits;
}

MatcherOptions MatchOptionsFor() {
  MatcherOptions options;
  options.min_score = 0.0;  // judged here, per use
  options.min_points = 20;
  return options;
}

// The MAP pose from two estimates of it with information in their (nearly common) vehicle
// frame: the prediction moved towards the match by the match's share of the information.
Se2 Fuse(const Se2& prediction, const Eigen::Matrix3d& prediction_information, const Se2& match,
         const Eigen::Matrix3d& match_information) {
  const Eigen::Vector3d difference = graph::BetweenError(prediction, match, Se2());
  const Eigen::Vector3d step =
      (prediction_information + match_information).ldlt().solve(match_information * difference);
  return prediction * Se2(step.head<2>(), step.z());
}

}  // namespace

MapBuilder::MapBuilder(const MapBuilderOptions& options)
    : options_(options),
      matcher_(LimitsFor(options), MatchOptionsFor()),
      scan_(LimitsFor(options).max_points),
      scale_(options.odometry_scale),
      scale_estimate_(options.scale_max_sigma_m, options.max_scale_error) {
  stats_.odometry_scale = scale_;
}

std::vector<Eigen::Vector2d> MapBuilder::PrepareScan(std::span<const Eigen::Vector2d> points) {
  scan_.Clear();
  for (const Eigen::Vector2d& p : points) {
    if (p.norm() <= options_.point_range_m) scan_.Add(p);
  }
  scan_.VoxelDecimate(options_.decimation_m);
  return {scan_.points().begin(), scan_.points().end()};
}

bool MapBuilder::AddScan(double time_s, const Se2& odometry, std::span<const Eigen::Vector2d> points) {
  ++stats_.scans;
  if (!keyframes_.empty()) {
    const Se2 moved = keyframes_.back().odometry.Inverse() * odometry;
    if (moved.translation().norm() < options_.keyframe_distance_m &&
        std::abs(moved.theta()) < options_.keyframe_angle_rad) {
      return false;
    }
  }
  Keyframe keyframe;
  keyframe.time_s = time_s;
  keyframe.odometry = odometry;
  keyframe.points = PrepareScan(points);
  if (keyframes_.empty()) {
    keyframe.estimate = has_anchor_ ? anchor_ : odometry;
    keyframes_.push_back(std::move(keyframe));
    graph_.AddNode(keyframes_.back().estimate, /*fixed=*/true);
    tracking_factor_.push_back(-1);
    step_covariance_.push_back(Eigen::Matrix3d::Zero());
    ++stats_.keyframes;
    return true;
  }
  const Keyframe& previous = keyframes_.back();
  const Se2 step = ScaledStep(previous.odometry.Inverse() * odometry);
  keyframe.path_m = previous.path_m + step.translation().norm();
  keyframe.estimate = previous.estimate * step;
  keyframes_.push_back(std::move(keyframe));
  graph_.AddNode(keyframes_.back().estimate);
  tracking_factor_.push_back(-1);
  const std::size_t k = keyframes_.size() - 1;
  odometry_factors_.push_back(graph_.betweens.size());
  graph_.betweens.push_back({k - 1, k, step, OdometryInformation(step, options_.odometry)});
  step_covariance_.push_back(graph_.betweens.back().information.inverse());  // until tracking refines it
  ++stats_.keyframes;

  TrackNewest();
  CloseLoops();
  if (loops_since_optimization_ >= options_.optimize_every) OptimizeGraph();
  return true;
}

MatchResult MapBuilder::MatchAgainst(std::size_t k, std::size_t first, std::size_t last, const Se2& prediction,
                                     const SearchWindow& window) {
  const auto start = Clock::now();
  const double reach = options_.point_range_m + window.linear + 1.0;
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = -low;
  std::vector<Eigen::Vector2d> world;
  std::vector<std::uint32_t> source;  // the keyframe of each point
  for (std::size_t j = first; j <= last; ++j) {
    if (j == k) continue;
    for (const Eigen::Vector2d& p : keyframes_[j].points) {
      const Eigen::Vector2d q = keyframes_[j].estimate * p;
      if ((q - prediction.translation()).cwiseAbs().maxCoeff() > reach) continue;
      world.push_back(q);
      source.push_back(static_cast<std::uint32_t>(j));
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
  }
  MatchResult result;
  result.status = MatchStatus::kTooFewPoints;
  if (world.size() < 20) return result;
  // The map must hold the prediction's window too, or the match is refused as outside it.
  low = low.cwiseMin(prediction.translation() - Eigen::Vector2d::Constant(window.linear + 1.0));
  high = high.cwiseMax(prediction.translation() + Eigen::Vector2d::Constant(window.linear + 1.0));
  GridGeometry geometry;
  geometry.resolution = options_.match_resolution_m;
  geometry.origin = low - Eigen::Vector2d::Constant(2.0 * geometry.resolution);
  geometry.width = static_cast<int>(std::ceil((high.x() - geometry.origin.x()) / geometry.resolution)) + 2;
  geometry.height = static_cast<int>(std::ceil((high.y() - geometry.origin.y()) / geometry.resolution)) + 2;
  MatchGrid map(geometry);
  MarkVotedStructure(world, source, std::min<std::size_t>(options_.map_min_votes, last - first), map);
  if (map.OccupiedCount() < 20 || !matcher_.SetMap(map).ok()) {
    stats_.match_seconds += SecondsSince(start);
    return result;
  }
  result = matcher_.Match(keyframes_[k].points, prediction, window);
  stats_.match_seconds += SecondsSince(start);
  return result;
}

void MapBuilder::MarkVotedStructure(const std::vector<Eigen::Vector2d>& world, const std::vector<std::uint32_t>& source,
                                    std::size_t min_votes, MatchGrid& map) const {
  // Votes per 2 x 2 block of cells, so a wall seen by two keyframes a centimetre apart
  // still collects both; each keyframe votes once per block.
  const GridGeometry& g = map.geometry();
  const int block_width = (g.width + 1) / 2;
  const std::size_t blocks = static_cast<std::size_t>(block_width) * static_cast<std::size_t>((g.height + 1) / 2);
  std::vector<std::uint16_t> votes(blocks, 0);
  std::vector<std::uint32_t> last_voter(blocks, std::numeric_limits<std::uint32_t>::max());
  auto block_of = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2i cell = g.CellOf(p);
    return static_cast<std::size_t>(cell.y() / 2) * static_cast<std::size_t>(block_width) +
           static_cast<std::size_t>(cell.x() / 2);
  };
  for (std::size_t i = 0; i < world.size(); ++i) {
    const std::size_t b = block_of(world[i]);
    if (last_voter[b] == source[i]) continue;
    last_voter[b] = source[i];
    if (votes[b] < std::numeric_limits<std::uint16_t>::max()) ++votes[b];
  }
  for (const Eigen::Vector2d& p : world) {
    if (votes[block_of(p)] >= min_votes) map.MarkPoint(p);
  }
}

Eigen::Matrix3d MapBuilder::MatchInformation(const MatchResult& match) const {
  // The match covariance is in the map's axes; F2's translation error is in the vehicle's.
  const Eigen::Matrix2d r = match.map_T_vehicle.Rotation();
  Eigen::Matrix3d covariance = match.covariance;
  covariance.topLeftCorner<2, 2>() = r.transpose() * match.covariance.topLeftCorner<2, 2>() * r;
  covariance.topRightCorner<2, 1>() = r.transpose() * match.covariance.topRightCorner<2, 1>();
  covariance.bottomLeftCorner<1, 2>() = covariance.topRightCorner<2, 1>().transpose();
  const double floor_m = options_.match_sigma_floor_m * options_.match_sigma_floor_m;
  const double floor_rad = options_.match_sigma_floor_rad * options_.match_sigma_floor_rad;
  covariance += Eigen::Vector3d(floor_m, floor_m, floor_rad).asDiagonal().toDenseMatrix();
  return covariance.inverse();
}

void MapBuilder::TrackNewest() {
  const std::size_t k = keyframes_.size() - 1;
  const std::size_t first = k > static_cast<std::size_t>(options_.local_map_keyframes)
                                ? k - static_cast<std::size_t>(options_.local_map_keyframes)
                                : 0;
  const MatchResult match = MatchAgainst(k, first, k - 1, keyframes_[k].estimate, options_.tracking_window);
  if (!match.ok() || match.score < options_.tracking_min_score) {
    ++stats_.tracking_rejected;
    return;
  }
  ++stats_.tracking_accepted;
  const Keyframe& previous = keyframes_[k - 1];
  const Se2 matched_step = previous.estimate.Inverse() * match.map_T_vehicle;
  const Eigen::Matrix3d information = MatchInformation(match);
  const Eigen::Matrix3d& odometry_information = graph_.betweens[odometry_factors_.back()].information;
  Eigen::Matrix3d running_information = information;  // what the running estimate takes of the match
  if (options_.fuse_tracking) {
    Eigen::Matrix3d covariance = information.inverse();
    covariance(2, 2) += options_.fuse_heading_floor_rad * options_.fuse_heading_floor_rad;
    running_information = covariance.inverse();
  }
  step_covariance_[k] = (odometry_information + running_information).inverse();
  const Se2 estimate = options_.fuse_tracking
                           ? Fuse(keyframes_[k].estimate, odometry_information, match.map_T_vehicle, running_information)
                           : match.map_T_vehicle;
  keyframes_[k].estimate = estimate;
  graph_.nodes[k].estimate = estimate;
  tracking_factor_[k] = static_cast<std::ptrdiff_t>(graph_.betweens.size());
  graph_.betweens.push_back({k - 1, k, matched_step, information});
  UpdateScale(previous.odometry.Inverse() * keyframes_[k].odometry, matched_step, information);
}

void MapBuilder::OptimizeGraph() {
  const auto start = Clock::now();
  graph::OptimizerOptions optimizer;
  optimizer.max_iterations = 30;
  if (!drift_loops_.empty()) {  // held as Gaussians for one solve, then taken out again
    const std::size_t betweens = graph_.betweens.size();
    for (std::size_t i : drift_loops_) {
      const graph::MaxMixtureBetweenFactor& loop = graph_.mixture_betweens[i];
      graph_.betweens.push_back({loop.from, loop.to, loop.measurement, loop.mixture.components[0].information});
    }
    graph::Optimize(graph_, optimizer);
    graph_.betweens.resize(betweens);
    drift_loops_.clear();
  }
  graph::Optimize(graph_, optimizer);
  for (std::size_t i = 0; i < keyframes_.size(); ++i) keyframes_[i].estimate = graph_.nodes[i].estimate;
  ++stats_.optimizations;
  stats_.optimize_seconds += SecondsSince(start);
  loops_since_optimization_ = 0;
}

void MapBuilder::RefineSweep() {
  const std::size_t n = keyframes_.size();
  const auto side = static_cast<std::size_t>(options_.refine_keyframes);
  struct Refined {
    Se2 pose;                   // world_T_vehicle against the two-sided local map
    Eigen::Matrix3d covariance;  // vehicle frame, floored
  };
  std::vector<std::optional<Refined>> refined(n);
  for (std::size_t k = 1; k < n; ++k) {
    const std::size_t first = k > side ? k - side : 0;
    const std::size_t last = std::min(n - 1, k + side);
    const MatchResult match = MatchAgainst(k, first, last, keyframes_[k].estimate, options_.refine_window);
    if (!match.ok() || match.score < options_.tracking_min_score) continue;
    refined[k] = Refined{match.map_T_vehicle, MatchInformation(match).inverse()};
  }
  // Two neighbours refined against (nearly) the same map: their relative pose is what the
  // map says, whatever error the map shares with both. The odometry scale is estimated
  // afresh from these steps, free of the forward tracking's partial views (but see the
  // header: a map built from the estimates keeps their scale).
  scale_estimate_.Reset();
  for (std::size_t k = 2; k < n; ++k) {
    if (!refined[k] || !refined[k - 1]) continue;
    ++stats_.refined;
    const Se2 step = refined[k - 1]->pose.Inverse() * refined[k]->pose;
    const Eigen::Matrix3d information = (refined[k - 1]->covariance + refined[k]->covariance).inverse();
    UpdateScale(keyframes_[k - 1].odometry.Inverse() * keyframes_[k].odometry, step, information);
    if (tracking_factor_[k] < 0) {
      tracking_factor_[k] = static_cast<std::ptrdiff_t>(graph_.betweens.size());
      graph_.betweens.push_back({k - 1, k, step, information});
      continue;
    }
    graph::BetweenFactor& factor = graph_.betweens[static_cast<std::size_t>(tracking_factor_[k])];
    factor.measurement = step;
    factor.information = information;
  }
  // Too few refined steps pin the scale down (open roads: posts and trees, no wall across
  // the path): the forward tracking's estimate is biased short, so the given scale
  // (odometry_scale, nominally 1) is the better guess.
  if (options_.estimate_odometry_scale && !scale_estimate_.ready()) {
    scale_ = options_.odometry_scale;
    stats_.odometry_scale = scale_;
  }
}

void MapBuilder::Finish() {
  RescaleOdometryFactors();
  if (keyframes_.size() > 1) OptimizeGraph();
  stats_.refined = 0;
  for (int sweep = 0; sweep < options_.refine_sweeps && keyframes_.size() > 2; ++sweep) {
    RefineSweep();
    RescaleOdometryFactors();
    OptimizeGraph();
  }
  stats_.loop_switched_off = 0;
  for (const auto& factor : graph_.mixture_betweens) {
    const Eigen::Vector3d error = graph::BetweenError(graph_.nodes[factor.from].estimate,
                                                      graph_.nodes[factor.to].estimate, factor.measurement);
    if (graph::SelectMixtureComponent(factor.mixture, error).component != 0) ++stats_.loop_switched_off;
  }
}

void MapBuilder::TransformEstimate(const Se2& world_T_map) {
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    keyframes_[k].estimate = world_T_map * keyframes_[k].estimate;
    graph_.nodes[k].estimate = keyframes_[k].estimate;
  }
}

void MapBuilder::ScaleEstimate(double scale, const Eigen::Vector2d& centre) {
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    const Se2& e = keyframes_[k].estimate;
    keyframes_[k].estimate = Se2(centre + scale * (e.translation() - centre), e.theta());
    graph_.nodes[k].estimate = keyframes_[k].estimate;
  }
}

Se2 MapBuilder::CorrectedPose(double time_s, const Se2& odometry) const {
  if (keyframes_.empty()) return odometry;
  auto correction = [](const Keyframe& k) { return k.estimate * k.odometry.Inverse(); };
  auto after = std::lower_bound(keyframes_.begin(), keyframes_.end(), time_s,
                                [](const Keyframe& k, double t) { return k.time_s < t; });
  if (after == keyframes_.begin()) return correction(*after) * odometry;
  if (after == keyframes_.end()) return correction(keyframes_.back()) * odometry;
  const Keyframe& before = *(after - 1);
  const double s = (time_s - before.time_s) / (after->time_s - before.time_s);
  return Interpolate(correction(before), correction(*after), s) * odometry;
}

}  // namespace flat2d::localization::mapping
