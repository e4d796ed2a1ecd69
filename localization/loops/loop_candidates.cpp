#include "localization/loops/loop_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>

namespace flat2d::localization::loops {

namespace {

Eigen::Vector3d CentreOf(const LocalMapTrajectory& map) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& pose : map.map_T_pose) sum += pose.translation();
  return map.world_T_map * (sum / static_cast<double>(std::max<std::size_t>(1, map.map_T_pose.size())));
}

// The rotation from a path's first pose to its last: what a map's own stretch turns.
Eigen::Matrix3d TurnOf(const LocalMapTrajectory& map) {
  return map.map_T_pose.front().linear().transpose() * map.map_T_pose.back().linear();
}

bool FarEnoughAlongPath(const LocalMapTrajectory& reference, const LocalMapTrajectory& current, double separation_m) {
  return current.path_start_m - reference.path_start_m >= separation_m;
}

bool Accepted(const ShapeAlignment& fit, const LoopCandidateOptions& options) {
  return fit.pairs >= 3 && fit.rms_translation_m <= options.max_rms_translation_m &&
         fit.rms_rotation_rad <= options.max_rms_rotation_rad &&
         fit.matched_length_m >= options.min_matched_m;
}

bool WithinDriftBound(const LocalMapTrajectory& reference, const LocalMapTrajectory& current,
                      const Eigen::Isometry3d& reference_T_current, const LoopCandidateOptions& options) {
  if (options.drift_fraction <= 0.0) return true;
  const double radius = std::max(options.drift_min_radius_m,
                                 options.drift_fraction * (current.path_start_m - reference.path_start_m));
  return ((reference.world_T_map * reference_T_current).translation() - current.world_T_map.translation()).norm() <= radius;
}

// The best of several random associations of the newest map's middle pose with the past
// map's poses; none when no fit is accepted.
std::optional<ShapeAlignment> BestFit(const PathAround& reference, const PathAround& current, std::mt19937& random,
                                      const LoopCandidateOptions& options) {
  const int current_seed = current.first_own + current.own_count / 2;
  const auto own = std::span(reference.map_T_pose).subspan(static_cast<std::size_t>(reference.first_own),
                                                           static_cast<std::size_t>(reference.own_count));
  const std::vector<double> arcs = ArcLengths(own);
  std::vector<int> reference_poses;
  const double spacing = std::max(options.association_spacing_m, 1e-3);
  for (double arc = std::uniform_real_distribution<double>(0.0, spacing)(random); arc < arcs.back() + spacing; arc += spacing) {
    const auto nearest = std::lower_bound(arcs.begin(), arcs.end(), std::min(arc, arcs.back()));
    const int index = reference.first_own + static_cast<int>(nearest - arcs.begin());
    if (reference_poses.empty() || reference_poses.back() != index) reference_poses.push_back(index);
  }
  std::optional<ShapeAlignment> best;
  for (const int reference_seed : reference_poses) {
    const ShapeAlignment fit =
        AlignTrajectories(reference.map_T_pose, current.map_T_pose, reference_seed, current_seed, options.alignment);
    if (!Accepted(fit, options)) continue;
    if (!best || fit.rms_translation_m < best->rms_translation_m) best = fit;
  }
  return best;
}

}  // namespace

std::vector<LoopCandidate> DistanceCandidates(std::span<const LocalMapTrajectory> maps, int current,
                                              const LoopCandidateOptions& options) {
  std::vector<LoopCandidate> candidates;
  const auto& newest = maps[static_cast<std::size_t>(current)];
  const Eigen::Vector3d centre = CentreOf(newest);
  for (int r = 0; r < current; ++r) {
    const auto& past = maps[static_cast<std::size_t>(r)];
    if (!FarEnoughAlongPath(past, newest, options.min_path_separation_m)) continue;
    if ((CentreOf(past) - centre).norm() > options.distance_radius_m) continue;
    LoopCandidate candidate;
    candidate.reference = r;
    candidate.current = current;
    candidate.source = CandidateSource::kDistance;
    candidate.reference_T_current = past.world_T_map.inverse() * newest.world_T_map;
    candidates.push_back(candidate);
  }
  return candidates;
}

bool ChainCrossesFailure(const std::vector<bool>& tie_failed, int a, int b) {
  const auto last = static_cast<int>(tie_failed.size());
  for (int tie = std::max(std::min(a, b), 0); tie < std::min(std::max(a, b), last); ++tie) {
    if (tie_failed[static_cast<std::size_t>(tie)]) return true;
  }
  return false;
}

std::vector<LoopCandidate> TrajectoryShapeCandidates(std::span<const LocalMapTrajectory> maps, int current,
                                                     const LoopCandidateOptions& options) {
  std::vector<LoopCandidate> candidates;
  const auto& newest = maps[static_cast<std::size_t>(current)];
  if (!IsInformative(newest.map_T_pose, options.min_spread_m)) return candidates;
  // Online, the newest map has no path after it.
  const PathAround current_path = PathAroundMap(maps.first(static_cast<std::size_t>(current) + 1), current, options.context_m, 0.0);
  const Eigen::Matrix3d current_turn = TurnOf(newest);
  std::mt19937 random(options.random_seed + static_cast<std::uint32_t>(current));
  for (int r = 0; r < current; ++r) {
    const auto& past = maps[static_cast<std::size_t>(r)];
    if (!FarEnoughAlongPath(past, newest, options.min_path_separation_m)) continue;
    if (!IsInformative(past.map_T_pose, options.min_spread_m)) continue;
    if (Eigen::AngleAxisd(TurnOf(past).transpose() * current_turn).angle() > options.max_turn_difference_rad) continue;
    const PathAround reference_path = PathAroundMap(maps.first(static_cast<std::size_t>(current)), r, options.context_m, options.context_m);
    const auto fit = BestFit(reference_path, current_path, random, options);
    if (!fit || !WithinDriftBound(past, newest, fit->reference_T_current, options)) continue;
    LoopCandidate candidate;
    candidate.reference = r;
    candidate.current = current;
    candidate.source = CandidateSource::kTrajectoryShape;
    candidate.reference_T_current = fit->reference_T_current;
    candidate.rms_translation_m = fit->rms_translation_m;
    candidate.matched_length_m = fit->matched_length_m;
    candidates.push_back(candidate);
  }
  return candidates;
}

}  // namespace flat2d::localization::loops
