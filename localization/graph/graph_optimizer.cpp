#include "localization/graph/graph_optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "localization/graph/normal_equations.hpp"
#include "localization/graph/optimizer_loop.hpp"

namespace flat2d::localization::graph {
namespace {

bool HasGauge(const PoseGraph& graph) {
  const bool any_fixed = std::any_of(graph.nodes.begin(), graph.nodes.end(),
                                     [](const PoseNode& node) { return node.fixed; });
  return any_fixed || !graph.priors.empty() || !graph.mixture_priors.empty();
}

// F1 (se2_factors.hpp) for one node.
Se2 RetractSe2(const Se2& pose, const Eigen::Vector3d& delta) { return Retract(pose, delta); }

}  // namespace

std::string_view StopReasonName(StopReason reason) {
  switch (reason) {
    case StopReason::kConverged: return "converged";
    case StopReason::kMaxIterations: return "max_iterations";
    case StopReason::kNoProgress: return "no_progress";
    case StopReason::kLinearSolveFailed: return "linear_solve_failed";
  }
  return "unknown";
}

OptimizationResult Optimize(PoseGraph& graph, const OptimizerOptions& options) {
  return OptimizeNodes<NormalEquations>(graph, HasGauge(graph), options, &RetractSe2);
}

Result<Eigen::Matrix3d> MarginalCovariance(const Posterior& posterior, std::size_t node) {
  if (node >= posterior.block_of_node.size()) {
    return MakeError("marginal covariance: node index " + std::to_string(node) +
                     " out of range");
  }
  const int block = posterior.block_of_node[node];
  if (block < 0) {
    return MakeError("marginal covariance: node " + std::to_string(node) +
                     " is fixed and has no covariance");
  }
  SparseLdlt ldlt(posterior.information);
  if (ldlt.info() != Eigen::Success) {
    return MakeError("marginal covariance: the information matrix is singular");
  }
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(posterior.information.rows(), 3);
  unit.block<3, 3>(3 * block, 0).setIdentity();
  const Eigen::MatrixXd columns = ldlt.solve(unit);
  const Eigen::Matrix3d covariance = columns.block<3, 3>(3 * block, 0);
  return Eigen::Matrix3d(0.5 * (covariance + covariance.transpose()));
}

}  // namespace flat2d::localization::graph
