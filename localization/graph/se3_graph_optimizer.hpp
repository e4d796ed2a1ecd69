// Sparse Gauss-Newton and Levenberg-Marquardt on SE(3) pose graphs (thesis 3.4.2, Alg. 6,
// eqs. 3.66-3.70): the loop of optimizer_loop.hpp over the 6x6-block normal equations of
// se3_normal_equations.hpp, with the retraction G1 of se3_factors.hpp. Options, stop rules
// and the result are graph_optimizer.hpp's: LM with Nielsen's lambda schedule, a relative
// cost decrease below 1e-6 (SE-Sync's criterion) as convergence, H at the solution as the
// posterior information (6x6 blocks, (dt, w) per node).
//
// Gauge: nodes marked fixed (g2o FIX) hold it; without any, the first node is held. The
// objective is the factors' own (se3_costs.hpp): g2o's chi2 on a graph as read, SE-Sync's f
// after ToSeSyncProblem.
#pragma once

#include "localization/graph/graph_optimizer.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

// Moves graph.nodes[*].estimate to a (local) minimum of the graph's cost.
OptimizationResult Optimize(Se3PoseGraph& graph, const OptimizerOptions& options = {});

}  // namespace flat2d::localization::graph
