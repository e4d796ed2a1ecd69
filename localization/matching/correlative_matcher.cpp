#include "localization/matching/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flat2d::localization {
namespace {

bool AllFinite(std::span<const Eigen::Vector2d> points) {
  return std::all_of(points.begin(), points.end(),
                     [](const Eigen::Vector2d& p) { return p.allFinite(); });
}

double MaxRange(std::span<const Eigen::Vector2d> points) {
  double max_norm = 0.0;
  for (const Eigen::Vector2d& p : points) max_norm = std::max(max_norm, p.norm());
  return max_norm;
}

int WindowCells(const SearchWindow& window, double resolution) {
  return static_cast<int>(std::ceil(window.linear / resolution - 1.0e-9));
}

// Enough levels that one coarsest block covers the window, within the limit.
int LevelsFor(int window_cells, int max_levels) {
  int levels = 1;
  while ((1 << (levels - 1)) < 2 * window_cells + 1 && levels < max_levels) ++levels;
  return levels;
}

}  // namespace

std::string_view MatchStatusName(MatchStatus status) {
  switch (status) {
    case MatchStatus::kOk: return "ok";
    case MatchStatus::kNoMap: return "no map loaded";
    case MatchStatus::kInvalidInput: return "invalid input";
    case MatchStatus::kTooFewPoints: return "too few points";
    case MatchStatus::kOutsideMap: return "prediction outside the map";
    case MatchStatus::kScoreBelowThreshold: return "score below threshold";
    case MatchStatus::kAmbiguous: return "ambiguous: a distinct second peak";
  }
  return "unknown";
}

CorrelativeMatcher::CorrelativeMatcher(const MatcherLimits& limits, const MatcherOptions& options)
    : limits_(limits),
      options_(options),
      map_(NewMap()),
      scans_(limits.max_headings, limits.max_points),
      branch_and_bound_(BranchAndBound::RootCount(limits.max_headings, limits.max_window_cells,
                                                  limits.max_levels)),
      coarse_scan_(limits.max_points) {}

Status CorrelativeMatcher::SetMap(const MatchGrid& map) { return map_->Rebuild(map); }

std::unique_ptr<MatchMap> CorrelativeMatcher::NewMap() const {
  return std::make_unique<MatchMap>(limits_.max_map_cells, limits_.max_levels, options_.table);
}

std::unique_ptr<MatchMap> CorrelativeMatcher::ExchangeMap(std::unique_ptr<MatchMap> built) {
  map_.swap(built);
  return built;
}

MatchResult CorrelativeMatcher::Match(std::span<const Eigen::Vector2d> points,
                                      const Se2& prediction, const SearchWindow& window) {
  return Search(points, prediction, window, /*exhaustive=*/false, options_.step_range_cap);
}

MatchResult CorrelativeMatcher::Relocalize(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                                           const SearchWindow& window, const RelocalizationOptions& relocalization) {
  coarse_scan_.Clear();
  for (std::size_t i = 0; i < points.size() && i < coarse_scan_.capacity(); ++i) coarse_scan_.Add(points[i]);
  coarse_scan_.VoxelDecimate(relocalization.decimation_m);
  const MatchResult coarse = Search(coarse_scan_.points(), prediction, window, /*exhaustive=*/false,
                                    std::min(relocalization.step_range_cap_m, options_.step_range_cap));
  if (!coarse.ok()) return coarse;
  MatchResult fine = Search(points, coarse.map_T_vehicle, {relocalization.refine_linear_m, relocalization.refine_angular_rad},
                            /*exhaustive=*/false, options_.step_range_cap);
  fine.evaluated_candidates += coarse.evaluated_candidates;
  fine.headings += coarse.headings;
  fine.second_peak_score = std::max(fine.second_peak_score, coarse.second_peak_score);
  return fine;
}

MatchResult CorrelativeMatcher::MatchExhaustive(std::span<const Eigen::Vector2d> points,
                                                const Se2& prediction,
                                                const SearchWindow& window) {
  return Search(points, prediction, window, /*exhaustive=*/true, options_.step_range_cap);
}

MatchStatus CorrelativeMatcher::CheckInput(std::span<const Eigen::Vector2d> points,
                                           const Se2& prediction,
                                           const SearchWindow& window) const {
  if (!has_map()) return MatchStatus::kNoMap;
  if (!prediction.Vector().allFinite() || !(window.linear >= 0.0) || !(window.angular >= 0.0) ||
      !std::isfinite(window.linear) || !std::isfinite(window.angular)) {
    return MatchStatus::kInvalidInput;
  }
  if (points.size() > limits_.max_points || !AllFinite(points)) return MatchStatus::kInvalidInput;
  if (WindowCells(window, map_->table().geometry().resolution) > limits_.max_window_cells) {
    return MatchStatus::kInvalidInput;
  }
  if (points.size() < std::max<std::size_t>(options_.min_points, 1)) {
    return MatchStatus::kTooFewPoints;
  }
  const Eigen::Vector2i cell = map_->table().geometry().CellOf(prediction.translation());
  if (!map_->table().geometry().Contains(cell.x(), cell.y())) return MatchStatus::kOutsideMap;
  return MatchStatus::kOk;
}

SearchProblem CorrelativeMatcher::Prepare(std::span<const Eigen::Vector2d> points,
                                          const Se2& prediction, const SearchWindow& window,
                                          double step_range_cap, HeadingSet& headings) {
  const double resolution = map_->table().geometry().resolution;
  const double step_range = std::min(MaxRange(points), step_range_cap);
  headings = ChooseHeadings(resolution, step_range, window.angular, options_.angular_step,
                            limits_.max_headings);
  scans_.Prepare(points, prediction, headings, map_->table().geometry());
  SearchProblem problem;
  problem.scans = &scans_;
  problem.table = &map_->table();
  problem.pyramid = &map_->pyramid();
  problem.window_cells = WindowCells(window, resolution);
  problem.levels = LevelsFor(problem.window_cells, limits_.max_levels);
  problem.separation_cells = static_cast<int>(options_.ambiguity_separation_m / resolution);
  problem.separation_headings =
      static_cast<int>(options_.ambiguity_separation_rad / std::max(headings.step, 1.0e-12));
  problem.headings_wrap = headings.count * headings.step > 2.0 * std::numbers::pi - 1.0e-9;
  return problem;
}

MatchResult CorrelativeMatcher::Search(std::span<const Eigen::Vector2d> points,
                                       const Se2& prediction, const SearchWindow& window,
                                       bool exhaustive, double step_range_cap) {
  MatchResult result;
  result.map_T_vehicle = prediction;
  result.points = points.size();
  result.status = CheckInput(points, prediction, window);
  if (result.status != MatchStatus::kOk) return result;

  HeadingSet headings;
  const SearchProblem problem = Prepare(points, prediction, window, step_range_cap, headings);
  const SearchOutcome outcome =
      exhaustive ? ExhaustiveSearch(problem) : branch_and_bound_.Search(problem);
  result.headings = headings.count;
  result.angular_step = headings.step;
  result.evaluated_candidates = outcome.evaluated;

  const double resolution = map_->table().geometry().resolution;
  const Candidate& best = outcome.best;
  const Se2 grid_pose(prediction.x() + best.x * resolution, prediction.y() + best.y * resolution,
                      prediction.theta() + headings.Offset(best.heading));
  result.map_T_vehicle = RefineContinuous(map_->table(), points, grid_pose, options_.refine_iterations,
                                          resolution, std::max(headings.step, 1.0e-3));
  result.covariance =
      SurfaceCovariance(problem, best, resolution, headings.step, options_.surface);
  Judge(points, outcome, result);
  return result;
}

void CorrelativeMatcher::Judge(std::span<const Eigen::Vector2d> points,
                               const SearchOutcome& outcome, MatchResult& result) const {
  const double full = kMaxCellScore * static_cast<double>(points.size());
  result.score = std::max(outcome.best.score, 0) / full;
  result.second_peak_score = std::max(outcome.second.score, 0) / full;
  if (result.score < options_.min_score) {
    result.status = MatchStatus::kScoreBelowThreshold;
  } else if (options_.ambiguity_ratio > 0.0 &&
             result.second_peak_score >= options_.ambiguity_ratio * result.score) {
    result.status = MatchStatus::kAmbiguous;
  } else {
    result.status = MatchStatus::kOk;
  }
}

}  // namespace flat2d::localization
