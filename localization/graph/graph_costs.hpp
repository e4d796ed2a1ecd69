// The two cost conventions of ../shared/data/posegraph/REFERENCE_RESULTS.md, which must not
// be mixed:
//  (1a) SE-Sync's objective (Rosen et al., IJRR 2019, eq. 12), no factor 1/2:
//       f = sum tau |tj - ti - Ri tz|^2 + kappa |Rj - Ri Rz|_F^2,
//       tau = 2 / trace((L_tt)^-1), kappa = L_thth, |Rj - Ri Rz|_F^2 = 4 (1 - cos(angle));
//  (1b) g2o's chi2 = sum e^T L e with F2's error (wrapped angle) and the file's information.
// Both are evaluated on a graph as read from its file (betweens with the file's information).
// ToSeSyncProblem() rewrites such a graph so that the optimizer's cost IS f: each between
// gets the chord angle residual and the information diag(tau, tau, 2 kappa) (see
// se2_factors.hpp), the optimum of which is the published f*.
#pragma once

#include <Eigen/Core>

#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

struct SeSyncWeights {
  double tau = 0.0;    // isotropic translational weight
  double kappa = 0.0;  // rotational weight
};
SeSyncWeights SeSyncWeightsOf(const Eigen::Matrix3d& information);

// (1b) over the between factors at the nodes' estimates.
double G2oChi2(const PoseGraph& graph);
// (1a) over the between factors at the nodes' estimates.
double SeSyncCost(const PoseGraph& graph);

// sum e^T L e over the between factors with their own information and angle residual: what
// the optimizer minimizes over them (SeSyncCost after ToSeSyncProblem, G2oChi2 before).
double BetweenCost(const PoseGraph& graph);

// The same graph with the between factors weighted and shaped so its cost is SeSyncCost.
PoseGraph ToSeSyncProblem(PoseGraph graph);

}  // namespace flat2d::localization::graph
