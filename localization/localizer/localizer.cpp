#include "localization/localizer/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "hal/common/thread_cpu_time.hpp"
#include "maps/grid/cell_class.hpp"

namespace flat2d::localization {
namespace {

// Added to the odometry's covariance before inverting it: standing still, dead reckoning
// says "no motion, no noise" (dead_reckoning.hpp D6), which is not an information matrix.
const Eigen::Matrix3d kOdometryCovarianceFloor = Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal();

double PositionSigma(const Eigen::Matrix3d& covariance) {
  return std::sqrt(std::max(covariance(0, 0), covariance(1, 1)));
}

MatcherLimits LimitsFor(const LocalizerOptions& options, const MapWindow& window) {
  MatcherLimits limits;
  limits.max_points = options.max_scan_points;
  limits.max_map_cells = window.grid().geometry().CellCount();
  const double widest = std::max(options.tracking_window.linear, options.relocalization_max_radius_m);
  limits.max_window_cells = static_cast<int>(std::ceil(widest / window.grid().resolution())) + 2;
  limits.max_headings = 1024;
  return limits;
}

MatcherOptions MatcherOptionsFor() {
  MatcherOptions options;
  options.min_score = 0.0;  // judged by the localizer: tracking and relocalization differ
  options.min_points = 20;
  return options;
}

}  // namespace

Result<Localizer> Localizer::Create(maps::PriorMapReader map, const LocalizerOptions& options) {
  if (Status valid = ValidateOptions(options); !valid.ok()) return valid.error();
  auto window = MapWindow::Create(map, options.map_window);
  if (!window.ok()) return window.error();
  std::optional<MapWindow> spare_window;
  if (options.map_prefetch) {
    auto spare = MapWindow::Create(map, options.map_window);
    if (!spare.ok()) return spare.error();
    spare_window.emplace(std::move(*spare));
  }
  auto graph = graph::SlidingWindowGraph::Create(options.graph);
  if (!graph.ok()) return graph.error();
  return Localizer(std::move(map), options, std::move(*window), std::move(spare_window), std::move(*graph));
}

Localizer::Localizer(maps::PriorMapReader map, const LocalizerOptions& options, MapWindow window,
                     std::optional<MapWindow> spare_window, graph::SlidingWindowGraph graph)
    : options_(options),
      map_(std::make_unique<maps::PriorMapReader>(std::move(map))),
      window_(std::move(window)),
      matcher_(LimitsFor(options, window_), MatcherOptionsFor()),
      scan_(options.max_grid_points),
      graph_(std::move(graph)) {
  if (spare_window) prefetch_ = std::make_unique<MapPrefetch>(std::move(*spare_window), matcher_.NewMap());
}

void Localizer::SetInitialPose(TimeNs time_ns, const Se2& global_T_vehicle, const Eigen::Matrix3d& covariance) {
  has_initial_pose_ = true;
  initial_time_ns_ = time_ns;
  initial_pose_ = global_T_vehicle;
  initial_covariance_ = covariance;
}

RevolutionReport Localizer::AddGrid(const maps::PublishedGrid& grid, const PoseHistory& odometry) {
  RevolutionReport report;
  report.state = state_;
  if (grid.grid == nullptr || !grid.complete) return report;
  ++stats_.grids;
  if (grid.fans_without_pose > 0) {  // placed without odometry: neither the scan nor its pose is known
    ++stats_.grids_without_odometry;
    return report;
  }
  const TimeNs time_ns = grid.start_ns;
  const Se2 local_T_vehicle = Se2Of(grid.local_T_grid);
  if (has_initial_pose_) StartFromInitialPose(time_ns, local_T_vehicle, odometry);
  if (!has_fix_ || time_ns <= last_node_ns_) return report;
  report.used = true;

  const double start = ThreadCpuSeconds();
  ExtractScan(*grid.grid);
  const Se2 prediction = global_T_local_ * local_T_vehicle;
  const MatchResult match = MatchScan(prediction, time_ns, odometry, report);
  const double matched = ThreadCpuSeconds();
  report.match_s = matched - start;
  Track(time_ns, local_T_vehicle, prediction, match, odometry, report);
  report.solve_s = ThreadCpuSeconds() - matched;
  CountUnmatched(time_ns, report.match_accepted);
  UpdateState(time_ns, PositionSigma(last_node_covariance_));
  report.state = state_;
  return report;
}

void Localizer::StartFromInitialPose(TimeNs time_ns, const Se2& local_T_vehicle, const PoseHistory& odometry) {
  has_initial_pose_ = false;
  // The pose was given at its own time: odometry carries it to the grid's.
  Se2 pose = initial_pose_;
  Eigen::Matrix3d covariance = initial_covariance_;
  const RelativeMotion motion = odometry.Between(initial_time_ns_, time_ns);
  if (motion.ok()) {
    pose = initial_pose_ * motion.a_T_b;
    covariance = ComposeCovariance(initial_pose_, initial_covariance_, motion.a_T_b, motion.covariance);
  }
  Restart(time_ns - 1, pose, (covariance + kOdometryCovarianceFloor).inverse());
  global_T_local_ = pose * local_T_vehicle.Inverse();
  last_accepted_ns_ = time_ns;
  unmatched_ns_ = 0;
  last_grid_ns_ = 0;
  ever_localized_ = false;
  const double sigma_m = PositionSigma(covariance);
  const double sigma_rad = std::sqrt(covariance(2, 2));
  relocalizing_ = 3.0 * sigma_m > options_.tracking_window.linear || 3.0 * sigma_rad > options_.tracking_window.angular;
  relocalization_window_ = {
      std::clamp(3.0 * sigma_m, options_.tracking_window.linear, options_.relocalization_max_radius_m),
      std::clamp(3.0 * sigma_rad, options_.tracking_window.angular, std::numbers::pi)};
  state_ = relocalizing_ ? LocalizerState::kLost : LocalizerState::kInitializing;
}

void Localizer::ExtractScan(const maps::ClassGrid& grid) {
  scan_.Clear();
  const maps::GridGeometry& g = grid.geometry();
  const std::span<const maps::CellClass> cells = grid.cells();
  const double range2 = options_.point_range_m * options_.point_range_m;
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (cells[g.Offset({col, row})] != maps::CellClass::kSlammable) continue;
      const Eigen::Vector2d p = g.CellCenter({col, row});
      if (p.squaredNorm() <= range2) scan_.Add(p);
    }
  }
  // The matcher takes at most max_scan_points: coarser squares until the scan fits.
  double voxel = options_.decimation_m;
  scan_.VoxelDecimate(voxel);
  while (scan_.size() > options_.max_scan_points) {
    voxel *= 1.25;
    scan_.VoxelDecimate(voxel);
  }
}

SearchWindow Localizer::TrackingWindow(TimeNs time_ns, const PoseHistory& odometry) const {
  SearchWindow window = options_.tracking_window;
  const GlobalPose predicted = PoseAt(time_ns, odometry);
  if (predicted.ok) {
    window.linear = std::clamp(3.0 * PositionSigma(predicted.covariance), options_.tracking_window.linear,
                               options_.max_tracking_window_m);
  }
  return window;
}

MatchResult Localizer::MatchScan(const Se2& prediction, TimeNs time_ns, const PoseHistory& odometry,
                                 RevolutionReport& report) {
  report.points = scan_.size();
  report.relocalizing = relocalizing_;
  // A global search wants the mosaic centred on its guess; tracking moves it every
  // recentre_m, or follows the nearest viewpoint.
  const bool viewpoints = options_.match_viewpoints && !relocalizing_ && map_->viewpoint_count() > 0;
  const double max_offset = relocalizing_ ? 1.0 : options_.map_window.recentre_m;
  const bool leaving_viewpoints = !viewpoints && window_.viewpoint() >= 0;
  Result<bool> moved = false;
  if (viewpoints) {
    DropPrefetch();
    moved = window_.CoverWithViewpoint(*map_, prediction.translation());
    if (moved.ok() && *moved && !matcher_.SetMap(window_.grid()).ok()) ++stats_.map_errors;
  } else {
    moved = CoverMosaic(prediction.translation(), leaving_viewpoints ? 0.0 : max_offset);
  }
  MatchResult result;
  if (!moved.ok()) {
    ++stats_.map_errors;
    result.status = MatchStatus::kNoMap;
    report.match = result.status;
    return result;
  }
  if (*moved) ++stats_.map_window_moves;
  if (relocalizing_) {
    ++stats_.relocalizations;
    result = matcher_.Relocalize(scan_.points(), prediction, relocalization_window_,
                                 options_.relocalization);
  } else {
    result = matcher_.Match(scan_.points(), prediction, TrackingWindow(time_ns, odometry));
  }
  report.match = result.status;
  report.score = result.score;
  report.headings = result.headings;
  report.match_pose = result.map_T_vehicle;
  report.match_covariance = result.covariance;
  return result;
}

Result<bool> Localizer::CoverMosaic(const Eigen::Vector2d& position, double max_offset_m) {
  const Eigen::Vector2d offset = position - window_.centre();
  const double recentre_m = options_.map_window.recentre_m;
  if (window_.filled() && window_.viewpoint() < 0 && offset.norm() < max_offset_m) {
    // Halfway to the move, in tracking: prepare the window around where the vehicle will be
    // when the move falls due, if it keeps its direction.
    if (prefetch_ && prefetch_->idle() && !relocalizing_ && offset.norm() >= 0.5 * recentre_m) {
      ++stats_.map_prefetches;
      prefetch_->Start(*map_, window_.centre() + offset.normalized() * recentre_m);
    }
    return false;
  }
  if (prefetch_ && !prefetch_->idle()) {
    const Status prepared = prefetch_->Finish();
    stats_.map_prefetch_cpu_s += prefetch_->last_job_cpu_s();
    if (prefetch_->last_finish_waited()) ++stats_.map_prefetch_waits;
    // Near its centre, the prepared window holds all it must (map_window.hpp); a global
    // search wants it as centred as a synchronous move would make it.
    const double take_within_m = std::min(0.5 * recentre_m, max_offset_m);
    if (prepared.ok() && (position - prefetch_->centre()).norm() < take_within_m) {
      prefetch_->Take(window_, matcher_);
      ++stats_.map_prefetches_taken;
      return true;
    }
    prefetch_->Discard();
  }
  const Result<bool> moved = window_.Cover(*map_, position, 0.0);
  if (!moved.ok()) return moved.error();
  if (!matcher_.SetMap(window_.grid()).ok()) ++stats_.map_errors;
  return true;
}

void Localizer::DropPrefetch() {
  if (!prefetch_ || prefetch_->idle()) return;
  (void)prefetch_->Finish();  // its result is not used
  stats_.map_prefetch_cpu_s += prefetch_->last_job_cpu_s();
  prefetch_->Discard();
}

void Localizer::WidenRelocalization() {
  SearchWindow& w = relocalization_window_;
  w.linear = std::min(w.linear * options_.relocalization_growth, options_.relocalization_max_radius_m);
  w.angular = std::min(w.angular * options_.relocalization_growth, std::numbers::pi);
}

bool Localizer::Accepts(const MatchResult& match) const {
  if (!match.ok()) return false;
  const double matched_points = match.score * static_cast<double>(match.points);
  if (relocalizing_) {
    return match.score >= options_.relocalization_min_score &&
           matched_points >= static_cast<double>(options_.relocalization_min_matched_points) &&
           match.second_peak_score <= options_.relocalization_max_peak_ratio * match.score;
  }
  const double min_score = ever_localized_ ? options_.min_score : options_.confirm_min_score;
  return match.score >= min_score && matched_points >= static_cast<double>(options_.min_matched_points);
}

Eigen::Matrix3d Localizer::MatchInformation(const Eigen::Matrix3d& covariance) const {
  const double m2 = options_.min_match_sigma_m * options_.min_match_sigma_m;
  const double r2 = options_.min_match_sigma_rad * options_.min_match_sigma_rad;
  const Eigen::Matrix3d floored = covariance + Eigen::Vector3d(m2, m2, r2).asDiagonal().toDenseMatrix();
  const Eigen::Matrix3d information = floored.inverse();
  return 0.5 * (information + information.transpose());
}

Eigen::Matrix3d Localizer::OdometryInformation(const RelativeMotion& motion) const {
  const double length = motion.a_T_b.translation().norm();
  const double linear = options_.odometry_sigma_per_m * length;
  const double angular = options_.odometry_sigma_rad_per_m * length;
  const Eigen::Matrix3d systematic = Eigen::Vector3d(linear * linear, linear * linear, angular * angular).asDiagonal();
  const Eigen::Matrix3d information = (motion.covariance + systematic + kOdometryCovarianceFloor).inverse();
  return 0.5 * (information + information.transpose());
}

void Localizer::Track(TimeNs time_ns, const Se2& local_T_vehicle, const Se2& prediction, const MatchResult& match,
                      const PoseHistory& odometry, RevolutionReport& report) {
  const bool passed = Accepts(match);
  if (relocalizing_) {
    if (!passed) {
      ++stats_.matches_rejected;
      WidenRelocalization();
      return;
    }
    // A global match replaces the window: the poses before it were wrong.
    ++stats_.relocalized;
    ++stats_.matches_accepted;
    Restart(time_ns, match.map_T_vehicle, MatchInformation(match.covariance));
    global_T_local_ = last_node_pose_ * local_T_vehicle.Inverse();
    relocalizing_ = false;
    confirmations_needed_ = options_.relocalization_confirmations;
    last_accepted_ns_ = time_ns;
    ever_localized_ = true;
    report.match_accepted = true;
    return;
  }

  const RelativeMotion motion = odometry.Between(last_node_ns_, time_ns);
  const graph::NodeId previous = graph_.newest_id();
  const Result<graph::NodeId> node = graph_.AddNode(time_ns, passed ? match.map_T_vehicle : prediction);
  if (!node.ok()) return;
  bool linked = false;
  if (motion.ok() && graph_.Contains(previous)) {
    linked = graph_.AddOdometry(previous, *node, motion.a_T_b, OdometryInformation(motion)).ok();
  }
  if (!linked) {  // the odometry's window no longer reaches the last node: start over from the prediction
    Restart(time_ns, prediction, (last_node_covariance_ + kOdometryCovarianceFloor).inverse());
  }
  const bool added = passed && graph_.AddMatch(graph_.newest_id(), match.map_T_vehicle,
                                              MatchInformation(match.covariance), options_.null_hypothesis).ok();
  const Result<graph::WindowSolution> solution = graph_.Solve(options_.solve_iterations);
  if (!solution.ok()) return;
  last_node_ns_ = time_ns;
  last_node_pose_ = solution->newest_global_T_vehicle;
  last_node_covariance_ = solution->newest_covariance;
  global_T_local_ = last_node_pose_ * local_T_vehicle.Inverse();
  const bool switched_off = graph_.NullMatches(graph_.newest_id()).value_or(0) > 0;
  report.match_accepted = added && !switched_off;
  if (report.match_accepted) {
    ++stats_.matches_accepted;
    last_accepted_ns_ = time_ns;
    ever_localized_ = true;
    if (confirmations_needed_ > 0) --confirmations_needed_;
  } else {
    ++stats_.matches_rejected;
    if (confirmations_needed_ > 0) {  // the global match was not confirmed: search on
      ++stats_.relocalizations_refuted;
      confirmations_needed_ = 0;
      relocalizing_ = true;
      WidenRelocalization();
    }
  }
}

void Localizer::Restart(TimeNs time_ns, const Se2& global_T_vehicle, const Eigen::Matrix3d& information) {
  graph_.Clear();
  const Result<graph::NodeId> node = graph_.AddNode(time_ns, global_T_vehicle);
  // A covariance that is not one (non-finite, not positive definite) falls back to a loose prior.
  if (node.ok() && !graph_.AddPrior(*node, global_T_vehicle, 0.5 * (information + information.transpose())).ok()) {
    (void)graph_.AddPrior(*node, global_T_vehicle, Eigen::Vector3d(1.0, 1.0, 100.0).asDiagonal());
  }
  has_fix_ = true;
  last_node_ns_ = time_ns;
  last_node_pose_ = global_T_vehicle;
  last_node_covariance_ = information.inverse();
}

void Localizer::CountUnmatched(TimeNs time_ns, bool accepted) {
  const TimeNs step = last_grid_ns_ == 0 ? 0 : std::min(time_ns - last_grid_ns_, kMaxRevolutionStep);
  last_grid_ns_ = time_ns;
  unmatched_ns_ = accepted ? 0 : unmatched_ns_ + step;
}

void Localizer::UpdateState(TimeNs time_ns, double position_sigma_m) {
  if (relocalizing_ || confirmations_needed_ > 0) {
    state_ = LocalizerState::kLost;
    return;
  }
  // LOST on evidence: revolutions that kept coming for lost_after without an accepted match,
  // or a position uncertainty beyond lost_sigma_m. A silent LiDAR is no evidence against the
  // pose: through silence odometry carries it, DEGRADED, until its uncertainty says LOST.
  const TimeNs since_match = time_ns - last_accepted_ns_;
  const TimeNs lost_after = ever_localized_ ? options_.lost_after_ns : options_.initial_lost_after_ns;
  if (unmatched_ns_ > lost_after || position_sigma_m > options_.lost_sigma_m) {
    state_ = LocalizerState::kLost;
    relocalizing_ = true;
    // Lost after tracking, the vehicle is where odometry says within its uncertainty: search
    // three standard deviations, not the whole radius a doubtful initial pose gets, so a
    // lookalike farther away cannot win.
    const double radius_m = ever_localized_ ? std::clamp(3.0 * position_sigma_m, options_.max_tracking_window_m,
                                                         options_.relocalization_radius_m)
                                            : options_.relocalization_radius_m;
    relocalization_window_ = {radius_m, std::numbers::pi};
  } else if (since_match > options_.degraded_after_ns) {
    state_ = ever_localized_ ? LocalizerState::kDegraded : LocalizerState::kInitializing;
  } else {
    state_ = ever_localized_ ? LocalizerState::kLocalized : LocalizerState::kInitializing;
  }
}

GlobalPose Localizer::PoseAt(TimeNs time_ns, const PoseHistory& odometry) const {
  return ComposeGlobalPose(fix(), odometry, time_ns);
}

void Localizer::Tick(TimeNs time_ns, const PoseHistory& odometry) {
  if (!has_fix_ || time_ns <= last_node_ns_) return;
  // The uncertainty of the pose served now: the last node's, grown by the odometry since.
  const GlobalPose now = ComposeGlobalPose(fix(), odometry, time_ns);
  UpdateState(time_ns, PositionSigma(now.ok ? now.covariance : last_node_covariance_));
}

LocalizationFix Localizer::fix() const {
  return {.has_fix = has_fix_,
          .node_ns = last_node_ns_,
          .node_pose = last_node_pose_,
          .node_covariance = last_node_covariance_,
          .global_T_local = global_T_local_,
          .state = state_,
          .last_accepted_ns = ever_localized_ ? last_accepted_ns_ : 0};
}

}  // namespace flat2d::localization
