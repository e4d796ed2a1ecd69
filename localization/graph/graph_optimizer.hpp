// Sparse Gauss-Newton and Levenberg-Marquardt on the SE(2) manifold (thesis 3.4.2, Alg. 6):
// linearize every factor at the current estimate (se2_factors.hpp), solve the sparse normal
// equations H dx = -b (normal_equations.hpp) with a simplicial LDL^T under an AMD ordering
// whose symbolic analysis is done once, and retract the increment onto the poses (F1).
//
// Gauge: the cost is invariant to moving the whole graph, so something must hold it. Nodes
// marked fixed (g2o FIX) or prior factors do; when the graph has neither, the first node is
// held. Levenberg-Marquardt damps H + lambda I with Nielsen's update of lambda (g2o's
// schedule); Gauss-Newton takes every step. Both stop when an accepted step changes the
// cost by less than `relative_decrease` of it (1e-6, SE-Sync's criterion), when the cost
// falls to round-off (1e-20 of the start: consistent measurements), or after
// `max_iterations` linear solves. The result carries H at the solution - the information
// matrix of the Laplace posterior - and MarginalCovariance() inverts a node's block of it.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <string_view>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

enum class Solver { kGaussNewton, kLevenbergMarquardt };

struct OptimizerOptions {
  Solver solver = Solver::kLevenbergMarquardt;
  int max_iterations = 100;
  double relative_decrease = 1e-6;
  // LM's first lambda as a multiple of H's largest diagonal entry (g2o's tau). g2o's 1e-5
  // damps the first steps from an odometry start so much that LM walks into local minima
  // of the chi2 on manhattan (146121 vs 3549) and city10000 (1485 vs 512); 1e-8 does not.
  double initial_lambda_scale = 1e-8;
};

enum class StopReason {
  kConverged,          // relative cost decrease below the threshold
  kMaxIterations,
  kNoProgress,         // LM rejected steps until lambda overflowed
  kLinearSolveFailed,  // H not positive definite (e.g. a node without constraints)
};
std::string_view StopReasonName(StopReason reason);

// H at the solution over the free nodes, full symmetric, with the map from nodes to blocks.
// It is the Hessian of the cost that was minimized: for a graph from ToSeSyncProblem it
// carries SE-Sync's isotropic weights, not the file's information. A node held for the
// gauge (the first one, when nothing else fixes it) has no block and no covariance; the
// others' covariances are then relative to it.
struct Posterior {
  Eigen::SparseMatrix<double> information;
  std::vector<int> block_of_node;  // -1 for fixed nodes
};

struct OptimizationResult {
  StopReason stop_reason = StopReason::kMaxIterations;
  int iterations = 0;                // linear solves, accepted or not
  std::vector<double> cost_history;  // the cost before the first and after each accepted step
  double seconds = 0.0;              // wall time of Optimize()
  Posterior posterior;

  bool converged() const { return stop_reason == StopReason::kConverged; }
  double initial_cost() const { return cost_history.front(); }
  double final_cost() const { return cost_history.back(); }
};

// Moves graph.nodes[*].estimate to a (local) minimum of the graph's cost.
OptimizationResult Optimize(PoseGraph& graph, const OptimizerOptions& options = {});

// The covariance (x, y, theta components, F1) of one node under the Laplace posterior;
// an error for fixed nodes, bad indices or a singular H.
Result<Eigen::Matrix3d> MarginalCovariance(const Posterior& posterior, std::size_t node);

}  // namespace flat2d::localization::graph
