#include "localization/graph/se3_graph_optimizer.hpp"

#include <algorithm>

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
  const bool any_fixed = std::any_of(graph.nodes.begin(), graph.nodes.end(),
                                     [](const Se3Node& node) { return node.fixed; });
  return OptimizeNodes<Se3NormalEquations>(graph, any_fixed, options, &RetractSe3);
}

}  // namespace flat2d::localization::graph
