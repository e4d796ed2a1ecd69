// Absolute and relative trajectory error of full 3D poses, in the conventions of the TUM RGB-D
// benchmark (Sturm et al., "A benchmark for the evaluation of RGB-D SLAM systems", IROS 2012;
// its evaluate_ate.py and evaluate_rpe.py). Steps:
//  1. Association: the truth is interpolated at each estimate pose's time (position linearly,
//     rotation by slerp) between its two poses around that time when they are at most
//     `max_gap_s` apart; a time within 2 us of a truth pose is that pose. The benchmark takes
//     the nearest truth pose instead; its truth runs at 100 Hz, so interpolating removes up to
//     5 ms of time offset per pose. Estimate poses the truth does not cover are counted.
//  2. ATE (Eq. 4-5): the rigid motion S (Horn / Umeyama, no scale) that best overlays the
//     estimate's positions on the truth's, then the distances |trans(Q_i^-1 S P_i)|.
//  3. RPE (Eq. 1-2): E_i = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) for pairs of estimate poses: every
//     consecutive pair (j = i + 1, "per frame"), and each i with j the first estimate pose at
//     least `rpe_delta_s` later. The translation's norm (m) and the rotation's angle (deg) of
//     each E_i are summarized by RMSE and median. RPE needs no alignment: it is invariant to
//     the estimate's and the truth's world frames.
// Q are truth poses, P estimate poses; trajectories are in increasing time order (ReadTum's).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/trajectory/tum_file.hpp"

namespace flat2d::localization::evaluation {

struct TrajectoryError3dOptions {
  double max_gap_s = 0.02;   // the benchmark's ATE association limit
  double rpe_delta_s = 1.0;  // the benchmark's default RPE interval
};

// One set of relative errors: pairs scored, RMSE and median of |translation| and |angle|.
struct RelativeError3d {
  std::size_t pairs = 0;
  double trans_rmse_m = 0.0;
  double rot_rmse_deg = 0.0;
  double trans_median_m = 0.0;
  double rot_median_deg = 0.0;
};

struct TrajectoryError3d {
  std::size_t poses_matched = 0;    // estimate poses the truth covers
  std::size_t poses_unmatched = 0;  // and those it does not
  Eigen::Isometry3d truth_T_estimate = Eigen::Isometry3d::Identity();  // the ATE alignment S
  double ate_rmse_m = 0.0;
  double ate_mean_m = 0.0;
  double ate_median_m = 0.0;  // nearest-rank (PercentilesOf)
  double ate_max_m = 0.0;
  RelativeError3d rpe_frame;  // per frame: m and deg per frame
  double rpe_delta_s = 0.0;
  RelativeError3d rpe_delta;  // over rpe_delta_s: m and deg over that interval
};

// The pose of `trajectory` at `time_ns`, interpolated; nullopt when no two poses at most
// `max_gap_ns` apart bracket it (a time within 2 us of a pose is that pose).
std::optional<Eigen::Isometry3d> InterpolatedPose(const std::vector<hal::trajectory::StampedPose>& trajectory,
                                                  TimeNs time_ns, TimeNs max_gap_ns);

// An error when the truth covers none of the estimate's poses.
Result<TrajectoryError3d> EvaluateTrajectory3d(const std::vector<hal::trajectory::StampedPose>& estimate,
                                               const std::vector<hal::trajectory::StampedPose>& truth,
                                               const TrajectoryError3dOptions& options = {});

}  // namespace flat2d::localization::evaluation
