// Loop-closure candidates scored against a truth trajectory (issue 12: "trajectory-shape
// candidates also on the real KITTI 00 truth trajectory, cut in 5 m pieces, seeded drift").
//
// Steps:
//  1. Drift: the truth's step-to-step motions, each with a wheel scale error, a yaw bias and
//     seeded random noise, chained from the first pose: a dead-reckoned estimate.
//  2. Local maps: the estimate cut every piece_length_m of its path; a map's frame is its
//     first pose, its internal trajectory the estimate relative to it, its graph pose the
//     drifted one.
//  3. Truth: maps r < c at least min_path_separation_m apart along the drive revisit each
//     other when at least min_overlap of c's truth positions lie within revisit_radius_m of
//     r's truth path; same direction when their truth headings are within 90 deg.
//  4. Candidates of loops/loop_candidates.hpp for every map in driving order; one is
//     correct when the pair overlaps at all and its guess is within tolerance of the truth
//     reference_T_current. Recall counts the same-direction revisits of informative maps.
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "localization/loops/loop_candidates.hpp"

namespace flat2d::localization::evaluation {

struct DriftModel {
  double scale_error = 0.005;                 // the wheels' distance, a fraction long
  double scale_noise = 0.01;                  // 1-sigma per step, fraction of the step
  double yaw_bias_deg_per_m = 0.005;          // an uncalibrated gyro
  double yaw_noise_deg_per_sqrt_m = 0.05;     // 1-sigma, random walk
  double tilt_noise_deg_per_sqrt_m = 0.02;    // roll and pitch, random walk
  std::uint32_t seed = 1;
};

// Step 1. world_T_vehicle poses (x forward, z up).
std::vector<Eigen::Isometry3d> DriftedTrajectory(std::span<const Eigen::Isometry3d> truth, const DriftModel& drift);

struct LocalMapCut {
  std::vector<loops::LocalMapTrajectory> maps;
  std::vector<int> first_pose;  // per map: index of its first pose in the trajectory
  std::vector<int> last_pose;   // inclusive; the next map's first
};
// Step 2.
LocalMapCut CutIntoLocalMaps(std::span<const Eigen::Isometry3d> estimate, double piece_length_m);

struct LoopEvalOptions {
  double piece_length_m = 5.0;
  DriftModel drift;
  loops::LoopCandidateOptions candidates;
  double revisit_radius_m = 2.0;
  double min_overlap = 0.5;
  double tolerance_m = 1.0;
  double tolerance_deg = 5.0;
};

struct CandidateScore {
  int candidates = 0;
  int correct = 0;
  int revisits_found = 0;      // of LoopEvalReport::informative_revisits
  int all_revisits_found = 0;  // of LoopEvalReport::revisits
  double precision() const { return candidates > 0 ? static_cast<double>(correct) / candidates : 0.0; }
};

struct LoopEvalReport {
  int poses = 0;
  double path_length_m = 0.0;
  double final_drift_m = 0.0;  // estimate vs truth at the last pose
  int maps = 0;
  int informative_maps = 0;
  int revisits = 0;               // same-direction revisiting pairs (step 3)
  int opposite_revisits = 0;      // pairs revisiting in the opposite direction (not counted in recall)
  int informative_revisits = 0;   // same direction, both maps informative: recall's denominator
  CandidateScore distance;
  CandidateScore shape;
  double shape_seconds = 0.0;     // the trajectory-shape search over all maps
  double recall(const CandidateScore& s) const {
    return informative_revisits > 0 ? static_cast<double>(s.revisits_found) / informative_revisits : 0.0;
  }
};

// Step 3 alone, for any cut (a build's local maps with the truth at their poses).
struct RevisitTruth {
  std::vector<bool> informative;                      // per map
  std::set<std::pair<int, int>> revisit_pairs;        // same direction, (reference, current)
  std::set<std::pair<int, int>> informative_pairs;    // ... both maps informative
  int opposite_revisits = 0;
};
RevisitTruth RevisitsOf(std::span<const Eigen::Isometry3d> truth, const LocalMapCut& cut, const LoopEvalOptions& options);

LoopEvalReport EvaluateLoopCandidates(std::span<const Eigen::Isometry3d> truth, const LoopEvalOptions& options);

}  // namespace flat2d::localization::evaluation
