// What a 3D registration returns (after small_gicp's result struct): the transform, the
// information it carries for fusion (H of the last linearisation), and how it went.
#pragma once

#include <string>

#include <Eigen/Geometry>

namespace flat2d::localization::registration {

enum class RegistrationFailure {
  kNone,
  kTooFewCorrespondences,  // fewer inliers than options.min_inliers at some iteration
  kDegenerate,             // the damped system could not be solved
};

const char* FailureName(RegistrationFailure failure);

struct RegistrationResult {
  // p_target = target_T_source * p_source (the thesis' T of Eq. 5.11: reference -> current).
  Eigen::Isometry3d target_T_source = Eigen::Isometry3d::Identity();
  // H = sum J^T Omega J at the solution, over (dt, dq) (Eq. 5.15): the information of the
  // estimate up to the scale of Omega.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  double chi2 = 0.0;         // sum of winsorized chi2 at the last iteration
  int correspondences = 0;   // pairs that passed the tests of 5.1.2
  int inliers = 0;           // of which chi2 below the winsorization bound K
  int iterations = 0;
  bool converged = false;    // the last step was below options.convergence_step
  RegistrationFailure failure = RegistrationFailure::kNone;

  bool ok() const { return failure == RegistrationFailure::kNone; }
};

}  // namespace flat2d::localization::registration
