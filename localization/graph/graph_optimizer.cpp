#include "localization/graph/graph_optimizer.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <string>

#include "localization/graph/normal_equations.hpp"

namespace flat2d::localization::graph {
namespace {

using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower,
                                   Eigen::AMDOrdering<int>>;

// Beyond this lambda the step is numerically zero: LM has nowhere left to go.
constexpr double kMaxLambda = 1e32;

bool HasGauge(const PoseGraph& graph) {
  const bool any_fixed = std::any_of(graph.nodes.begin(), graph.nodes.end(),
                                     [](const PoseNode& node) { return node.fixed; });
  return any_fixed || !graph.priors.empty() || !graph.mixture_priors.empty();
}

// x [+] dx for every free node (F1).
void RetractAll(std::span<const Se2> from, const Eigen::VectorXd& step,
                const std::vector<int>& block_of_node, std::vector<Se2>& to) {
  for (std::size_t n = 0; n < from.size(); ++n) {
    const int block = block_of_node[n];
    to[n] = block < 0 ? from[n] : Retract(from[n], step.segment<3>(3 * block));
  }
}

// A small change: a Gauss-Newton step that raised the cost a lot is not convergence, one
// that wobbles at the numerical floor is.
// A cost this far below the start is the round-off floor of consistent measurements.
constexpr double kCostFloor = 1e-20;

bool Converged(double cost_before, double cost_after, double relative_decrease,
               double initial_cost) {
  return std::abs(cost_before - cost_after) <= relative_decrease * cost_before ||
         cost_after <= kCostFloor * initial_cost;
}

// The iteration loop shared by both solvers; `estimates` holds the current poses.
class Iterations {
 public:
  Iterations(const PoseGraph& graph, const OptimizerOptions& options)
      : options_(options), equations_(graph), candidate_(graph.nodes.size()) {
    estimates_.reserve(graph.nodes.size());
    for (const PoseNode& node : graph.nodes) estimates_.push_back(node.estimate);
  }

  OptimizationResult Run() {
    OptimizationResult result;
    double cost = equations_.Linearize(estimates_);
    result.cost_history.push_back(cost);
    ldlt_.analyzePattern(equations_.hessian());
    double lambda = options_.initial_lambda_scale * equations_.MaxDiagonal();
    double nu = 2.0;
    const bool damped = options_.solver == Solver::kLevenbergMarquardt;
    while (result.iterations < options_.max_iterations) {
      ++result.iterations;
      if (damped) equations_.AddToDiagonal(lambda);
      ldlt_.factorize(equations_.hessian());
      if (damped) equations_.AddToDiagonal(-lambda);
      if (ldlt_.info() != Eigen::Success) {
        if (!damped) return Finish(result, StopReason::kLinearSolveFailed);
        lambda *= nu;  // damping makes H + lambda I definite eventually
        nu *= 2.0;
        continue;
      }
      step_ = -ldlt_.solve(equations_.gradient());
      RetractAll(estimates_, step_, equations_.block_of_node(), candidate_);
      const double new_cost = equations_.Cost(candidate_);
      if (damped) {
        // Predicted decrease of c + 2 b^T h + h^T H h with (H + lambda I) h = -b.
        const double predicted = lambda * step_.squaredNorm() - equations_.gradient().dot(step_);
        const double rho = (cost - new_cost) / std::max(predicted, 1e-300);
        if (!(new_cost < cost) || rho <= 0.0) {
          // A step that changes the cost by less than the tolerance either way: the cost is
          // at its numerical floor (e.g. exactly 0 for noise-free measurements).
          if (std::abs(new_cost - cost) <= options_.relative_decrease * cost) {
            return Finish(result, StopReason::kConverged);
          }
          lambda *= nu;
          nu *= 2.0;
          if (lambda > kMaxLambda) return Finish(result, StopReason::kNoProgress);
          continue;
        }
        const double shrink = 1.0 - std::pow(2.0 * rho - 1.0, 3.0);
        lambda *= std::max(1.0 / 3.0, shrink);
        nu = 2.0;
      }
      estimates_.swap(candidate_);
      const bool converged =
          Converged(cost, new_cost, options_.relative_decrease, result.cost_history.front());
      cost = equations_.Linearize(estimates_);
      result.cost_history.push_back(cost);
      if (converged) return Finish(result, StopReason::kConverged);
    }
    return Finish(result, StopReason::kMaxIterations);
  }

  const std::vector<Se2>& estimates() const { return estimates_; }

 private:
  OptimizationResult& Finish(OptimizationResult& result, StopReason reason) {
    result.stop_reason = reason;
    // H at the current estimate (Linearize ran there last); mirror the lower triangle.
    result.posterior.information =
        equations_.hessian().selfadjointView<Eigen::Lower>();
    result.posterior.block_of_node = equations_.block_of_node();
    return result;
  }

  const OptimizerOptions& options_;
  NormalEquations equations_;
  std::vector<Se2> estimates_;
  std::vector<Se2> candidate_;
  Eigen::VectorXd step_;
  Ldlt ldlt_;
};

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
  const auto start = std::chrono::steady_clock::now();
  const bool hold_first = !HasGauge(graph) && !graph.nodes.empty();
  if (hold_first) graph.nodes.front().fixed = true;
  Iterations iterations(graph, options);
  OptimizationResult result = iterations.Run();
  if (hold_first) graph.nodes.front().fixed = false;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    graph.nodes[n].estimate = iterations.estimates()[n];
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
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
  Ldlt ldlt(posterior.information);
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
