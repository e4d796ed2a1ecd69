#include "localization/graph/se3_graph_optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "localization/graph/optimizer_loop.hpp"
#include "localization/graph/se3_factors.hpp"
#include "localization/graph/se3_normal_equations.hpp"

namespace flat2d::localization::graph {
namespace {

// G1 for one node.
Eigen::Isometry3d RetractSe3(const Eigen::Isometry3d& pose, const Vector6d& delta) {
  return Retract(pose, delta);
}

}  // namespace

OptimizationResult Optimize(Se3PoseGraph& graph, const OptimizerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool any_fixed = std::any_of(graph.nodes.begin(), graph.nodes.end(),
                                     [](const Se3Node& node) { return node.fixed; });
  const bool hold_first = !any_fixed && !graph.nodes.empty();
  if (hold_first) graph.nodes.front().fixed = true;
  Se3NormalEquations equations(graph);
  std::vector<Eigen::Isometry3d> estimates;
  estimates.reserve(graph.nodes.size());
  for (const Se3Node& node : graph.nodes) estimates.push_back(node.estimate);
  OptimizerLoop loop(equations, std::move(estimates), options, &RetractSe3);
  OptimizationResult result = loop.Run();
  if (hold_first) graph.nodes.front().fixed = false;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    graph.nodes[n].estimate = loop.estimates()[n];
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace flat2d::localization::graph
