#include "localization/evaluation/loop_candidate_eval.hpp"

#include <chrono>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "hal/common/angles.hpp"
#include "localization/loops/trajectory_shape.hpp"

namespace flat2d::localization::evaluation {

namespace {

// Distance from a point to a polyline of positions.
double DistanceToPath(const Eigen::Vector3d& point, std::span<const Eigen::Isometry3d> path, int first, int last) {
  double best = (point - path[static_cast<std::size_t>(first)].translation()).norm();
  for (int i = first; i < last; ++i) {
    const Eigen::Vector3d a = path[static_cast<std::size_t>(i)].translation();
    const Eigen::Vector3d segment = path[static_cast<std::size_t>(i) + 1].translation() - a;
    const double squared = segment.squaredNorm();
    const double u = squared > 0.0 ? std::clamp((point - a).dot(segment) / squared, 0.0, 1.0) : 0.0;
    best = std::min(best, (point - (a + u * segment)).norm());
  }
  return best;
}

struct PairTruth {
  double overlap = 0.0;
  bool same_direction = false;
};

// Step 3 for maps r and c.
PairTruth TruthOf(std::span<const Eigen::Isometry3d> truth, const LocalMapCut& cut, int r, int c, double radius_m) {
  const auto r_index = static_cast<std::size_t>(r);
  const auto c_index = static_cast<std::size_t>(c);
  int near = 0;
  for (int i = cut.first_pose[c_index]; i <= cut.last_pose[c_index]; ++i) {
    if (DistanceToPath(truth[static_cast<std::size_t>(i)].translation(), truth, cut.first_pose[r_index],
                       cut.last_pose[r_index]) <= radius_m) {
      ++near;
    }
  }
  PairTruth result;
  result.overlap = static_cast<double>(near) / (cut.last_pose[c_index] - cut.first_pose[c_index] + 1);
  const auto heading = [&](std::size_t map) {
    return truth[static_cast<std::size_t>(cut.last_pose[map])].translation() -
           truth[static_cast<std::size_t>(cut.first_pose[map])].translation();
  };
  result.same_direction = heading(r_index).dot(heading(c_index)) > 0.0;
  return result;
}

bool GuessIsCorrect(std::span<const Eigen::Isometry3d> truth, const LocalMapCut& cut, const loops::LoopCandidate& candidate,
                    const LoopEvalOptions& options) {
  const Eigen::Isometry3d reference_T_current =
      truth[static_cast<std::size_t>(cut.first_pose[static_cast<std::size_t>(candidate.reference)])].inverse() *
      truth[static_cast<std::size_t>(cut.first_pose[static_cast<std::size_t>(candidate.current)])];
  const Eigen::Isometry3d error = reference_T_current.inverse() * candidate.reference_T_current;
  return error.translation().norm() <= options.tolerance_m &&
         Eigen::AngleAxisd(error.linear()).angle() <= options.tolerance_deg * kDegToRad;
}

// Scores one strategy's candidates; `revisit_pairs` / `informative_pairs` are step 3's.
void Score(std::span<const Eigen::Isometry3d> truth, const LocalMapCut& cut, const std::vector<loops::LoopCandidate>& candidates,
           const std::set<std::pair<int, int>>& revisit_pairs, const std::set<std::pair<int, int>>& informative_pairs,
           const LoopEvalOptions& options, CandidateScore& score) {
  std::set<std::pair<int, int>> found;
  for (const auto& candidate : candidates) {
    ++score.candidates;
    const bool overlaps = TruthOf(truth, cut, candidate.reference, candidate.current, options.revisit_radius_m).overlap > 0.0;
    if (!overlaps || !GuessIsCorrect(truth, cut, candidate, options)) continue;
    ++score.correct;
    found.insert({candidate.reference, candidate.current});
  }
  for (const auto& pair : found) {
    score.revisits_found += informative_pairs.count(pair) > 0 ? 1 : 0;
    score.all_revisits_found += revisit_pairs.count(pair) > 0 ? 1 : 0;
  }
}

}  // namespace

std::vector<Eigen::Isometry3d> DriftedTrajectory(std::span<const Eigen::Isometry3d> truth, const DriftModel& drift) {
  std::vector<Eigen::Isometry3d> estimate;
  if (truth.empty()) return estimate;
  std::mt19937 random(drift.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  estimate.push_back(truth.front());
  for (std::size_t i = 1; i < truth.size(); ++i) {
    Eigen::Isometry3d step = truth[i - 1].inverse() * truth[i];
    const double distance = step.translation().norm();
    step.translation() *= 1.0 + drift.scale_error + drift.scale_noise * normal(random);
    const double root = std::sqrt(distance);
    const double yaw = (drift.yaw_bias_deg_per_m * distance + drift.yaw_noise_deg_per_sqrt_m * root * normal(random)) * kDegToRad;
    const double roll = drift.tilt_noise_deg_per_sqrt_m * root * normal(random) * kDegToRad;
    const double pitch = drift.tilt_noise_deg_per_sqrt_m * root * normal(random) * kDegToRad;
    step.linear() = step.linear() * (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                        .toRotationMatrix();
    estimate.push_back(estimate.back() * step);
  }
  return estimate;
}

LocalMapCut CutIntoLocalMaps(std::span<const Eigen::Isometry3d> estimate, double piece_length_m) {
  LocalMapCut cut;
  const std::vector<double> arcs = loops::ArcLengths(estimate);
  int first = 0;
  for (int i = 1; i < static_cast<int>(estimate.size()); ++i) {
    const bool last = i + 1 == static_cast<int>(estimate.size());
    if (arcs[static_cast<std::size_t>(i)] - arcs[static_cast<std::size_t>(first)] < piece_length_m && !last) continue;
    loops::LocalMapTrajectory map;
    map.world_T_map = estimate[static_cast<std::size_t>(first)];
    map.path_start_m = arcs[static_cast<std::size_t>(first)];
    for (int k = first; k <= i; ++k) map.map_T_pose.push_back(map.world_T_map.inverse() * estimate[static_cast<std::size_t>(k)]);
    cut.maps.push_back(std::move(map));
    cut.first_pose.push_back(first);
    cut.last_pose.push_back(i);
    first = i;
  }
  return cut;
}

RevisitTruth RevisitsOf(std::span<const Eigen::Isometry3d> truth, const LocalMapCut& cut, const LoopEvalOptions& options) {
  RevisitTruth t;
  const int maps = static_cast<int>(cut.maps.size());
  for (const auto& map : cut.maps) t.informative.push_back(loops::IsInformative(map.map_T_pose, options.candidates.min_spread_m));
  for (int c = 0; c < maps; ++c) {
    for (int r = 0; r < c; ++r) {
      const auto& past = cut.maps[static_cast<std::size_t>(r)];
      const auto& newest = cut.maps[static_cast<std::size_t>(c)];
      if (newest.path_start_m - past.path_start_m < options.candidates.min_path_separation_m) continue;
      const PairTruth pair = TruthOf(truth, cut, r, c, options.revisit_radius_m);
      if (pair.overlap < options.min_overlap) continue;
      if (!pair.same_direction) {
        ++t.opposite_revisits;
        continue;
      }
      t.revisit_pairs.insert({r, c});
      if (t.informative[static_cast<std::size_t>(r)] && t.informative[static_cast<std::size_t>(c)]) t.informative_pairs.insert({r, c});
    }
  }
  return t;
}

LoopEvalReport EvaluateLoopCandidates(std::span<const Eigen::Isometry3d> truth, const LoopEvalOptions& options) {
  LoopEvalReport report;
  const std::vector<Eigen::Isometry3d> estimate = DriftedTrajectory(truth, options.drift);
  report.poses = static_cast<int>(truth.size());
  if (truth.size() < 2) return report;
  report.path_length_m = loops::ArcLengths(truth).back();
  report.final_drift_m = (estimate.back().translation() - truth.back().translation()).norm();
  const LocalMapCut cut = CutIntoLocalMaps(estimate, options.piece_length_m);
  report.maps = static_cast<int>(cut.maps.size());
  const RevisitTruth revisits = RevisitsOf(truth, cut, options);
  for (const bool i : revisits.informative) report.informative_maps += i ? 1 : 0;
  report.opposite_revisits = revisits.opposite_revisits;
  report.revisits = static_cast<int>(revisits.revisit_pairs.size());
  report.informative_revisits = static_cast<int>(revisits.informative_pairs.size());

  std::vector<loops::LoopCandidate> by_distance, by_shape;
  const auto start = std::chrono::steady_clock::now();
  for (int c = 0; c < report.maps; ++c) {
    const auto found = loops::TrajectoryShapeCandidates(cut.maps, c, options.candidates);
    by_shape.insert(by_shape.end(), found.begin(), found.end());
  }
  report.shape_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (int c = 0; c < report.maps; ++c) {
    const auto found = loops::DistanceCandidates(cut.maps, c, options.candidates);
    by_distance.insert(by_distance.end(), found.begin(), found.end());
  }
  Score(truth, cut, by_distance, revisits.revisit_pairs, revisits.informative_pairs, options, report.distance);
  Score(truth, cut, by_shape, revisits.revisit_pairs, revisits.informative_pairs, options, report.shape);
  return report;
}

}  // namespace flat2d::localization::evaluation
