// Two local maps' internal trajectories aligned by their shape (thesis 6.3.2, Eq. 6.13):
//   T* = argmin_T sum_C || toVector(T_m^r^-1 T T_n^c) ||^2,   Omega = I,
// toVector(T) = (t, q_xyz), the error of graph/se3_factors.hpp (G2). Where a vehicle passes
// the same road or tunnel twice its path is nearly the same, so aligning the paths gives the
// loop closure's initial guess before any point is registered.
//
// Steps, from one association (m0, n0) of a reference pose with a current pose:
//  1. T = T_m0^r T_n0^c^-1.
//  2. Correspondences along both trajectories by path length, within initial_span_m of
//     n0: current pose n goes with the reference pose (interpolated) as far along the
//     reference from m0 as n is from n0, so two passes at different speeds pair up.
//  3. Gauss-Newton on Eq. 6.13 (6 unknowns, the retraction G1 of T), each term under a
//     Huber kernel: where the passes begin to part, within the gate of step 4, their
//     pairs would otherwise pull the fit (our addition; Omega stays I).
//  4. Growth: the correspondences extended outward from n0 along the whole current path
//     until a pair's position error exceeds max_pair_distance_m (where the passes part);
//     step 3 again, until the number of pairs stops changing.
//  5. The association is good to a pose spacing at best, and the error it leaves along
//     the path is what Eq. 6.13 alone corrects worst (only the path's curvature holds it):
//     steps 2-4 are repeated for path offsets within offset_search_m of the association's,
//     on a coarse and then a fine grid, and the fit with the least mean squared error kept;
//     unless the association's own fit is off by more than search_limit_m (RMS of the 6D
//     error): most associations tried belong to no loop, and the search would not save them.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Geometry>

namespace flat2d::localization::loops {

struct ShapeAlignmentOptions {
  int max_iterations = 10;      // Gauss-Newton per association
  double huber_m = 0.2;         // step 3's kernel, on the norm of the 6D error
  int max_reassociations = 8;   // step 4 rounds
  double offset_search_m = 1.0; // step 5
  double search_limit_m = 1.0;
  double initial_span_m = 5.0;  // step 2: about a local map
  // Step 4 stops growing at the first current pose farther than this from its partner
  // after alignment: the two passes part there.
  double max_pair_distance_m = 1.0;
};

struct ShapeAlignment {
  Eigen::Isometry3d reference_T_current = Eigen::Isometry3d::Identity();  // T*
  int pairs = 0;                       // correspondences in the last solve
  double rms_translation_m = 0.0;      // of the last solve's errors
  double rms_rotation_rad = 0.0;       // 2 asin |q_xyz|, RMS
  double matched_length_m = 0.0;       // current path length whose both ends have partners
};

// One term of Eq. 6.13 and its Jacobian with respect to a G1 perturbation of T.
struct ShapeLinearization {
  Eigen::Matrix<double, 6, 1> error;
  Eigen::Matrix<double, 6, 6> jacobian;
};
ShapeLinearization LinearizeShapeError(const Eigen::Isometry3d& reference_T_current, const Eigen::Isometry3d& reference_pose,
                                       const Eigen::Isometry3d& current_pose);

// The pose along a path `arc_m` metres from its start (linear in position, slerp in
// rotation), clamped to the path's ends. `arc_lengths` are the poses' distances from the first.
Eigen::Isometry3d PoseAlongPath(std::span<const Eigen::Isometry3d> path, std::span<const double> arc_lengths,
                                double arc_m);

// Cumulative path length at each pose (the first 0).
std::vector<double> ArcLengths(std::span<const Eigen::Isometry3d> path);

// Steps 1-5. Poses are map_T_pose in each map's own frame. Empty paths or seeds out of
// range give an alignment with no pairs.
ShapeAlignment AlignTrajectories(std::span<const Eigen::Isometry3d> reference, std::span<const Eigen::Isometry3d> current,
                                 int reference_seed, int current_seed, const ShapeAlignmentOptions& options = {});

}  // namespace flat2d::localization::loops
