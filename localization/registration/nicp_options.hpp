// Options of NICP registration (thesis 5.1.2-5.1.3, 5.3), field by field. The thesis'
// values are the defaults; where it gives none (K, lambda) the chosen value says why.
#pragma once

namespace flat2d::localization::registration {

enum class ErrorMetric {
  kNicp,           // 6D point + normal error, Omega = diag(Omega^s, Omega^n) (Eq. 5.13)
  kPointToPlane,   // Omega^n = 0, pairs by distance only: the thesis' point-to-plane baseline (5.1.3, 5.3)
};

struct NicpOptions {
  ErrorMetric metric = ErrorMetric::kNicp;
  float max_distance_m = 0.5F;          // eps_d, Eq. 5.6
  float max_log_curvature_ratio = 1.3F;  // eps_sigma, Eq. 5.7
  // Eq. 5.7 compares sigmas raised to at least this. The thesis leaves flat patches to the
  // test as fitted (0, the default); the NICP authors' implementation raises both sigmas
  // to its flatness cut, so two flat patches always agree (their sigmas are noise: a
  // plane's 1e-4 and 1e-3 differ by more than e^1.3). At 0.02 (the cut of Eq. 5.2 here)
  // KITTI pairs land 1.9 mm further from their truth (docs/benchmarks.md).
  float curvature_floor = 0.0F;
  float min_normal_dot = 0.95F;          // eps_n, Eq. 5.8
  // K of Eq. 4.11. A flat point's Omega^s is 1/eps = 1000 along its normal, so K = 10
  // is 10 cm off the plane: beyond, a pair's pull stops growing. K = 1 (3 cm) holds back
  // a LiDAR pair 0.5 m apart (10 iterations reach 0.14 m of it); depth pairs do not care.
  double chi2_bound = 10.0;
  // lambda of Eq. 5.15, relative to the mean diagonal of H, so the damping is the same
  // for 1000 or 300000 pairs.
  double damping = 1e-4;
  // Scales Omega^n: 1 is Eq. 5.14 as written (Fig. 5.8 varies it), for normals fitted over
  // R = 0.1 m. RegisterFrames() scales it by (R / 0.1 m)^2: a normal fitted over R wobbles
  // by about sigma_p / R, so against the points' metres its information goes with R^2
  // (on the 15 cm bunny, R = 3 mm, the unscaled term drags a pair 3.5 deg off its truth).
  double normal_weight = 1.0;
  int iterations = 10;                   // 5.3
  int min_inliers = 100;
  // Stop early when a step moves less than this (metres and quaternion imaginary part).
  double convergence_step = 1e-6;
  // KD-tree mode: nearest neighbours on (p, alpha n) (Eq. 6.10).
  float kdtree_alpha = 1.0F / 3.0F;
  // Thesis Eq. 6.7: each pair's terms scaled by w_i w_j, w = 1/d the point's depth in its
  // own sensor frame (Eq. 6.4's weight: far points are noisier). Projective mode only (a
  // KD-tree's target is a map, not a view). chi2 and the inlier count stay unweighted.
  bool inverse_depth_weights = false;
};

}  // namespace flat2d::localization::registration
