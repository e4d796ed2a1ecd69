// The Gauss-Newton / Levenberg-Marquardt iteration shared by the SE(2) and SE(3) batch
// optimizers (thesis 3.4.2, Alg. 6; the options, stop rules and result are those of
// graph_optimizer.hpp): factorize H (+ lambda I) with a simplicial LDL^T under an AMD
// ordering analysed once, solve H dx = -b, retract dx onto the poses, accept or reject.
//
// `Equations` linearizes one pose type: Linearize(span<const Pose>) fills H and b and returns
// the cost, Cost(span<const Pose>) only scores, AddToDiagonal, MaxDiagonal, hessian(),
// gradient(), block_of_node() and kBlockSize (the tangent dimension) as in
// normal_equations.hpp. `Retract(pose, delta)` applies one node's increment.
#pragma once

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "localization/graph/graph_optimizer.hpp"

namespace flat2d::localization::graph {

using SparseLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower,
                                         Eigen::AMDOrdering<int>>;

template <typename Equations, typename Pose, typename RetractFn>
class OptimizerLoop {
 public:
  // Beyond this lambda the step is numerically zero: LM has nowhere left to go.
  static constexpr double kMaxLambda = 1e32;
  // A cost this far below the start is the round-off floor of consistent measurements.
  static constexpr double kCostFloor = 1e-20;

  OptimizerLoop(Equations& equations, std::vector<Pose> estimates, const OptimizerOptions& options,
                RetractFn retract)
      : options_(options),
        equations_(equations),
        estimates_(std::move(estimates)),
        candidate_(estimates_),
        retract_(retract) {}

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
      RetractAll();
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
      const bool converged = Converged(cost, new_cost, result.cost_history.front());
      cost = equations_.Linearize(estimates_);
      result.cost_history.push_back(cost);
      if (converged) return Finish(result, StopReason::kConverged);
    }
    return Finish(result, StopReason::kMaxIterations);
  }

  const std::vector<Pose>& estimates() const { return estimates_; }

 private:
  static constexpr int kBlock = Equations::kBlockSize;

  // A small change: a Gauss-Newton step that raised the cost a lot is not convergence, one
  // that wobbles at the numerical floor is.
  bool Converged(double cost_before, double cost_after, double initial_cost) const {
    return std::abs(cost_before - cost_after) <= options_.relative_decrease * cost_before ||
           cost_after <= kCostFloor * initial_cost;
  }

  // x [+] dx for every free node.
  void RetractAll() {
    const std::vector<int>& block_of_node = equations_.block_of_node();
    for (std::size_t n = 0; n < estimates_.size(); ++n) {
      const int block = block_of_node[n];
      candidate_[n] = block < 0 ? estimates_[n]
                                : retract_(estimates_[n], step_.template segment<kBlock>(kBlock * block));
    }
  }

  OptimizationResult& Finish(OptimizationResult& result, StopReason reason) {
    result.stop_reason = reason;
    // H at the current estimate (Linearize ran there last); mirror the lower triangle.
    result.posterior.information = equations_.hessian().template selfadjointView<Eigen::Lower>();
    result.posterior.block_of_node = equations_.block_of_node();
    return result;
  }

  const OptimizerOptions& options_;
  Equations& equations_;
  std::vector<Pose> estimates_;
  std::vector<Pose> candidate_;
  RetractFn retract_;
  Eigen::VectorXd step_;
  SparseLdlt ldlt_;
};

// Runs the loop on `graph`'s node estimates and writes them back. Without a gauge of its own
// (`has_gauge` false: no fixed node, no prior) the first node is held for the run. Graph
// has `nodes` with `estimate` and `fixed`; Equations is built from the graph.
template <typename Equations, typename Graph, typename RetractFn>
OptimizationResult OptimizeNodes(Graph& graph, bool has_gauge, const OptimizerOptions& options, RetractFn retract) {
  const auto start = std::chrono::steady_clock::now();
  const bool hold_first = !has_gauge && !graph.nodes.empty();
  if (hold_first) graph.nodes.front().fixed = true;
  Equations equations(graph);
  using Pose = std::decay_t<decltype(graph.nodes.front().estimate)>;
  std::vector<Pose> estimates;
  estimates.reserve(graph.nodes.size());
  for (const auto& node : graph.nodes) estimates.push_back(node.estimate);
  OptimizerLoop loop(equations, std::move(estimates), options, retract);
  OptimizationResult result = loop.Run();
  if (hold_first) graph.nodes.front().fixed = false;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) graph.nodes[n].estimate = loop.estimates()[n];
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace flat2d::localization::graph
