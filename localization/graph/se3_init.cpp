#include "localization/graph/se3_init.hpp"

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <string>
#include <vector>

#include "localization/graph/anchored_laplacian.hpp"
#include "localization/graph/se3_costs.hpp"

namespace flat2d::localization::graph {
namespace {

// node_to's pose from node_from's through factor f, whichever way f points.
Eigen::Isometry3d Across(const Se3PoseGraph& graph, const Se3BetweenFactor& f, std::size_t node_from) {
  const Eigen::Isometry3d& origin = graph.nodes[node_from].estimate;
  return f.from == node_from ? origin * f.measurement : origin * f.measurement.inverse();
}

// For each node k > 0 the between factor joining k-1 and k, or -1.
std::vector<long> ChainEdges(const Se3PoseGraph& graph) {
  std::vector<long> chain(graph.nodes.size(), -1);
  for (std::size_t e = 0; e < graph.betweens.size(); ++e) {
    const Se3BetweenFactor& f = graph.betweens[e];
    const std::size_t later = std::max(f.from, f.to);
    if (later == std::min(f.from, f.to) + 1 && chain[later] < 0) chain[later] = static_cast<long>(e);
  }
  return chain;
}

// Composes chain edges forward and backward from `start` over nodes not yet reached.
void PropagateAlongChain(Se3PoseGraph& graph, const std::vector<long>& chain, std::size_t start,
                         std::vector<bool>& reached) {
  for (std::size_t k = start + 1; k < graph.nodes.size() && chain[k] >= 0 && !reached[k]; ++k) {
    graph.nodes[k].estimate = Across(graph, graph.betweens[static_cast<std::size_t>(chain[k])], k - 1);
    reached[k] = true;
  }
  for (std::size_t k = start; k > 0 && chain[k] >= 0 && !reached[k - 1]; --k) {
    graph.nodes[k - 1].estimate = Across(graph, graph.betweens[static_cast<std::size_t>(chain[k])], k);
    reached[k - 1] = true;
  }
}

// The nearest rotation (Frobenius norm) to a 3x3 matrix.
Eigen::Matrix3d ProjectToSo3(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d middle = Eigen::Matrix3d::Identity();
  middle(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * middle * svd.matrixV().transpose();
}

// Step (1): min sum kappa |R_j - R_i R_z|_F^2 with R_0 held. Unknowns: per node k > 0 the
// block U_k = R_k^T (column r is row r of R_k), residual U_j - R_z^T U_i.
Result<std::vector<Eigen::Matrix3d>> RelaxedRotations(const Se3PoseGraph& graph) {
  const auto n = static_cast<Eigen::Index>(graph.nodes.size());
  const Eigen::Matrix3d anchor = graph.nodes.front().estimate.linear().transpose();  // U_0
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(3 * (n - 1), 3);
  auto add_block = [&](Eigen::Index r, Eigen::Index c, const Eigen::Matrix3d& value) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) triplets.emplace_back(3 * (r - 1) + a, 3 * (c - 1) + b, value(a, b));
    }
  };
  for (const Se3BetweenFactor& f : graph.betweens) {
    const double kappa = SeSyncWeightsOf(f.information).kappa;
    const Eigen::Matrix3d rz = f.measurement.linear();
    const auto i = static_cast<Eigen::Index>(f.from);
    const auto j = static_cast<Eigen::Index>(f.to);
    const Eigen::Matrix3d identity = kappa * Eigen::Matrix3d::Identity();  // R_z R_z^T = I
    if (i > 0) add_block(i, i, identity);
    if (j > 0) add_block(j, j, identity);
    if (i > 0 && j > 0) {
      add_block(i, j, -kappa * rz);
      add_block(j, i, -kappa * rz.transpose());
    }
    if (i == 0 && j > 0) rhs.middleRows<3>(3 * (j - 1)) += kappa * rz.transpose() * anchor;
    if (j == 0 && i > 0) rhs.middleRows<3>(3 * (i - 1)) += kappa * rz * anchor;
  }
  Eigen::SparseMatrix<double> system(3 * (n - 1), 3 * (n - 1));
  system.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(system);
  if (ldlt.info() != Eigen::Success) return MakeError("chordal initialization: singular system");
  const Eigen::MatrixXd solution = ldlt.solve(rhs);
  std::vector<Eigen::Matrix3d> rotations(graph.nodes.size(), anchor.transpose());
  for (Eigen::Index k = 1; k < n; ++k) {
    rotations[static_cast<std::size_t>(k)] =
        ProjectToSo3(solution.middleRows<3>(3 * (k - 1)).transpose());
  }
  return rotations;
}

}  // namespace

Status InitializeFromOdometry(Se3PoseGraph& graph) {
  if (graph.nodes.empty()) return Status::Ok();
  const std::vector<long> chain = ChainEdges(graph);
  std::vector<bool> reached(graph.nodes.size(), false);
  reached[0] = true;
  PropagateAlongChain(graph, chain, 0, reached);
  // Where the chain breaks, bridge with any edge from a reached node and go on from there.
  for (bool bridged = true; bridged;) {
    bridged = false;
    for (const Se3BetweenFactor& f : graph.betweens) {
      if (reached[f.from] == reached[f.to]) continue;
      const std::size_t source = reached[f.from] ? f.from : f.to;
      const std::size_t target = reached[f.from] ? f.to : f.from;
      graph.nodes[target].estimate = Across(graph, f, source);
      reached[target] = true;
      PropagateAlongChain(graph, chain, target, reached);
      bridged = true;
    }
  }
  const auto unreached = std::find(reached.begin(), reached.end(), false);
  if (unreached != reached.end()) {
    const auto node = static_cast<std::size_t>(unreached - reached.begin());
    return MakeError("odometry initialization: vertex " + std::to_string(graph.nodes[node].id) +
                     " is not connected to vertex " + std::to_string(graph.nodes[0].id));
  }
  return Status::Ok();
}

Status InitializeChordal(Se3PoseGraph& graph) {
  if (graph.nodes.size() < 2) return Status::Ok();
  const Result<std::vector<Eigen::Matrix3d>> rotations = RelaxedRotations(graph);
  if (!rotations) return rotations.error();
  const std::size_t edges = graph.betweens.size();
  std::vector<EdgeEnds> ends(edges);
  std::vector<double> tau(edges);
  Eigen::MatrixXd translation_delta(static_cast<Eigen::Index>(edges), 3);
  for (std::size_t e = 0; e < edges; ++e) {
    const Se3BetweenFactor& f = graph.betweens[e];
    ends[e] = {f.from, f.to};
    tau[e] = SeSyncWeightsOf(f.information).tau;
    translation_delta.row(static_cast<Eigen::Index>(e)) =
        ((*rotations)[f.from] * f.measurement.translation()).transpose();
  }
  const Eigen::Vector3d anchor = graph.nodes.front().estimate.translation();
  const Result<Eigen::MatrixXd> positions = SolveAnchoredLaplacian(
      graph.nodes.size(), ends, tau, translation_delta, anchor.transpose());
  if (!positions) return positions.error();
  for (std::size_t n = 1; n < graph.nodes.size(); ++n) {
    Eigen::Isometry3d& pose = graph.nodes[n].estimate;
    pose.linear() = (*rotations)[n];
    pose.translation() = positions->row(static_cast<Eigen::Index>(n - 1)).transpose();
  }
  return Status::Ok();
}

Status Initialize(Se3PoseGraph& graph, Initialization init) { return InitializeBy(graph, init); }

}  // namespace flat2d::localization::graph
