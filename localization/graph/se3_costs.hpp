// The two cost conventions of ../shared/data/posegraph/REFERENCE_RESULTS.md for SE(3) graphs
// (graph_costs.hpp has them for SE(2)); neither has a factor 1/2 and they must not be mixed:
//  (1a) SE-Sync's objective (Rosen et al., IJRR 2019, eq. 12):
//       f = sum kappa |R_j - R_i R_z|_F^2 + tau |t_j - t_i - R_i t_z|^2,
//       tau = 3 / trace(inv(L_tt)), kappa = 3 / (2 trace(inv(L_RR))) from the 6x6
//       information L (translation block first); its off-diagonal blocks are ignored;
//  g2o chi2 = sum e^T L e with g2o's own EDGE_SE3:QUAT error (se3_factors.hpp, G2: the
//       quaternion's vector part, unscaled) and the file's information.
// Both are evaluated on a graph as read from its file. ToSeSyncProblem() rewrites such a
// graph so that the optimizer's cost IS f: each between gets the information
// diag(tau I, 8 kappa I) over the same error (|R_j - R_i R_z|_F^2 = 8 |q.vec|^2, G2).
#pragma once

#include <Eigen/Geometry>

#include "localization/graph/graph_costs.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

// (1a)'s 3D weights of one edge's information.
SeSyncWeights SeSyncWeightsOf(const Matrix6d& information);

// g2o's chi2 over the between factors at the nodes' estimates, with their information:
// the file's on a graph as read (what the optimizer minimizes), f after ToSeSyncProblem.
double G2oChi2(const Se3PoseGraph& graph);
// (1a) over the between factors at the nodes' estimates, from the file's information.
double SeSyncCost(const Se3PoseGraph& graph);

// One factor's term e^T L e at the poses of its two nodes.
double BetweenCost(const Se3BetweenFactor& factor, const Eigen::Isometry3d& pose_from,
                   const Eigen::Isometry3d& pose_to);

// The same graph with every between factor weighted so its cost is f.
Se3PoseGraph ToSeSyncProblem(Se3PoseGraph graph);

}  // namespace flat2d::localization::graph
