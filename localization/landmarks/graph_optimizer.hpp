// Levenberg-Marquardt on the manifold of the landmark graph (thesis 3.2, Algorithm 2, and
// 3.4.2): poses move by RetractPose (F1), planes and lines by their own retractions
// (plane.hpp P1, line.hpp A.17-A.18), points by addition (point_factor.hpp), with
// iteratively reweighted robust kernels on the landmark factors.
//
// Steps per iteration: linearize at the estimate (normal_equations.hpp); solve
// (H + lambda diag(H)) dx = -b with a sparse LDLT (Eigen::SimplicialLDLT, AMD ordering,
// one symbolic analysis per call); apply dx on the manifold; keep the step if the robust
// cost fell, else raise lambda and solve again. Stops after `max_iterations` accepted or
// refused steps, when the cost falls by less than a relative `min_relative_decrease`, or
// when lambda passes `max_lambda` (no step helps: a minimum to the solver's precision).
#pragma once

#include "localization/landmarks/landmark_graph.hpp"
#include "localization/landmarks/normal_equations.hpp"

namespace flat2d::localization::landmarks {

struct OptimizerOptions {
  KernelChoice kernel;               // on the landmark factors; odometry is trusted
  int min_landmark_observations = 2;  // landmarks seen fewer times stay out of the solve
  double initial_lambda = 1e-4;      // LM damping relative to diag(H) on the first step
  double max_lambda = 1e4;           // past this, no step lowers the cost: stop
  double min_relative_decrease = 1e-6;  // convergence: relative cost decrease per step
};

struct OptimizationResult {
  int iterations = 0;        // steps tried (accepted + refused)
  int refused_steps = 0;     // steps that raised the cost and were undone
  int variables = 0;         // dimension of dx
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int downweighted_factors = 0;  // weight < 1/2 at the last linearization
  bool converged = false;
  bool factorization_failed = false;  // H + lambda diag(H) not positive definite: nothing moved
  double milliseconds = 0.0;
};

// Moves the nodes of `graph` towards the minimum of its robust cost: all of them, or with
// first_free_pose > 1 the window of normal_equations.hpp (MakeLayout).
OptimizationResult OptimizeGraph(LandmarkGraph& graph, const OptimizerOptions& options, int max_iterations,
                                 int first_free_pose = 1);

}  // namespace flat2d::localization::landmarks
