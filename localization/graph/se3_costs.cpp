#include "localization/graph/se3_costs.hpp"

#include <Eigen/LU>

#include "localization/graph/se3_factors.hpp"

namespace flat2d::localization::graph {

SeSyncWeights SeSyncWeightsOf(const Matrix6d& information) {
  const Eigen::Matrix3d translation = information.topLeftCorner<3, 3>();
  const Eigen::Matrix3d rotation = information.bottomRightCorner<3, 3>();
  return {3.0 / translation.inverse().trace(), 3.0 / (2.0 * rotation.inverse().trace())};
}

double BetweenCost(const Se3BetweenFactor& factor, const Eigen::Isometry3d& pose_from,
                   const Eigen::Isometry3d& pose_to) {
  const Vector6d e = Se3BetweenError(pose_from, pose_to, factor.measurement);
  return e.dot(factor.information * e);
}

double G2oChi2(const Se3PoseGraph& graph) {
  double chi2 = 0.0;
  for (const Se3BetweenFactor& f : graph.betweens) {
    chi2 += BetweenCost(f, graph.nodes[f.from].estimate, graph.nodes[f.to].estimate);
  }
  return chi2;
}

double SeSyncCost(const Se3PoseGraph& graph) {
  // Written from eq. 12 directly rather than through the factors, as an independent check.
  double f = 0.0;
  for (const Se3BetweenFactor& edge : graph.betweens) {
    const Eigen::Isometry3d& xi = graph.nodes[edge.from].estimate;
    const Eigen::Isometry3d& xj = graph.nodes[edge.to].estimate;
    const SeSyncWeights w = SeSyncWeightsOf(edge.information);
    const Eigen::Vector3d dt =
        xj.translation() - xi.translation() - xi.linear() * edge.measurement.translation();
    const Eigen::Matrix3d dr = xj.linear() - xi.linear() * edge.measurement.linear();
    f += w.tau * dt.squaredNorm() + w.kappa * dr.squaredNorm();
  }
  return f;
}

Se3PoseGraph ToSeSyncProblem(Se3PoseGraph graph) {
  for (Se3BetweenFactor& f : graph.betweens) {
    const SeSyncWeights w = SeSyncWeightsOf(f.information);
    Vector6d diagonal;
    diagonal << w.tau, w.tau, w.tau, 8.0 * w.kappa, 8.0 * w.kappa, 8.0 * w.kappa;
    f.information = diagonal.asDiagonal();
  }
  return graph;
}

}  // namespace flat2d::localization::graph
