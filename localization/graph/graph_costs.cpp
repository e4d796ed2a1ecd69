#include "localization/graph/graph_costs.hpp"

#include <Eigen/LU>
#include <cmath>

namespace flat2d::localization::graph {

SeSyncWeights SeSyncWeightsOf(const Eigen::Matrix3d& information) {
  const Eigen::Matrix2d translation = information.topLeftCorner<2, 2>();
  return {2.0 / translation.inverse().trace(), information(2, 2)};
}

double G2oChi2(const PoseGraph& graph) {
  double chi2 = 0.0;
  for (const BetweenFactor& f : graph.betweens) {
    const Eigen::Vector3d e = BetweenError(graph.nodes[f.from].estimate, graph.nodes[f.to].estimate,
                                           f.measurement, AngleResidual::kWrapped);
    chi2 += e.dot(f.information * e);
  }
  return chi2;
}

double BetweenCost(const PoseGraph& graph) {
  double cost = 0.0;
  for (const BetweenFactor& f : graph.betweens) {
    const Eigen::Vector3d e = BetweenError(graph.nodes[f.from].estimate, graph.nodes[f.to].estimate,
                                           f.measurement, f.angle);
    cost += e.dot(f.information * e);
  }
  return cost;
}

double SeSyncCost(const PoseGraph& graph) {
  // Written from eq. 12 directly rather than through the factors, as an independent check.
  double f = 0.0;
  for (const BetweenFactor& edge : graph.betweens) {
    const Se2& pi = graph.nodes[edge.from].estimate;
    const Se2& pj = graph.nodes[edge.to].estimate;
    const SeSyncWeights w = SeSyncWeightsOf(edge.information);
    const Eigen::Vector2d dt =
        pj.translation() - pi.translation() - pi.Rotation() * edge.measurement.translation();
    const double angle = pj.theta() - pi.theta() - edge.measurement.theta();
    f += w.tau * dt.squaredNorm() + w.kappa * 4.0 * (1.0 - std::cos(angle));
  }
  return f;
}

PoseGraph ToSeSyncProblem(PoseGraph graph) {
  for (BetweenFactor& f : graph.betweens) {
    const SeSyncWeights w = SeSyncWeightsOf(f.information);
    f.information = Eigen::Vector3d(w.tau, w.tau, 2.0 * w.kappa).asDiagonal();
    f.angle = AngleResidual::kChord;
  }
  return graph;
}

}  // namespace flat2d::localization::graph
