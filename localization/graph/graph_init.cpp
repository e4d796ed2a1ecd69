#include "localization/graph/graph_init.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "localization/graph/anchored_laplacian.hpp"
#include "localization/graph/graph_costs.hpp"

namespace flat2d::localization::graph {
namespace {

// For each node k > 0 the between factor joining k-1 and k, or -1.
std::vector<long> ChainEdges(const PoseGraph& graph) {
  std::vector<long> chain(graph.nodes.size(), -1);
  for (std::size_t e = 0; e < graph.betweens.size(); ++e) {
    const BetweenFactor& f = graph.betweens[e];
    const std::size_t later = std::max(f.from, f.to);
    if (later == std::min(f.from, f.to) + 1 && chain[later] < 0) chain[later] = static_cast<long>(e);
  }
  return chain;
}

// Composes chain edges forward and backward from `start` over nodes not yet reached.
void PropagateAlongChain(PoseGraph& graph, const std::vector<long>& chain, std::size_t start,
                         std::vector<bool>& reached) {
  for (std::size_t k = start + 1; k < graph.nodes.size() && chain[k] >= 0 && !reached[k]; ++k) {
    const BetweenFactor& f = graph.betweens[static_cast<std::size_t>(chain[k])];
    graph.nodes[k].estimate =
        graph.nodes[k - 1].estimate * (f.to == k ? f.measurement : f.measurement.Inverse());
    reached[k] = true;
  }
  for (std::size_t k = start; k > 0 && chain[k] >= 0 && !reached[k - 1]; --k) {
    const BetweenFactor& f = graph.betweens[static_cast<std::size_t>(chain[k])];
    graph.nodes[k - 1].estimate =
        graph.nodes[k].estimate * (f.to == k ? f.measurement.Inverse() : f.measurement);
    reached[k - 1] = true;
  }
}

// The between factors' node pairs, for SolveAnchoredLaplacian.
std::vector<EdgeEnds> EdgeEndsOf(const PoseGraph& graph) {
  std::vector<EdgeEnds> ends;
  ends.reserve(graph.betweens.size());
  for (const BetweenFactor& f : graph.betweens) ends.push_back({f.from, f.to});
  return ends;
}

}  // namespace

std::string_view InitializationName(Initialization init) {
  switch (init) {
    case Initialization::kFile: return "file";
    case Initialization::kOdometry: return "odometry";
    case Initialization::kChordal: return "chordal";
  }
  return "unknown";
}

Status InitializeFromOdometry(PoseGraph& graph) {
  if (graph.nodes.empty()) return Status::Ok();
  const std::vector<long> chain = ChainEdges(graph);
  std::vector<bool> reached(graph.nodes.size(), false);
  reached[0] = true;
  PropagateAlongChain(graph, chain, 0, reached);
  // Where the chain breaks (a missing i -> i+1 edge), bridge with any edge from a reached
  // node and continue along the chain from there.
  for (bool bridged = true; bridged;) {
    bridged = false;
    for (const BetweenFactor& f : graph.betweens) {
      if (reached[f.from] == reached[f.to]) continue;
      const std::size_t target = reached[f.from] ? f.to : f.from;
      graph.nodes[target].estimate = reached[f.from]
                                         ? graph.nodes[f.from].estimate * f.measurement
                                         : graph.nodes[f.to].estimate * f.measurement.Inverse();
      reached[target] = true;
      PropagateAlongChain(graph, chain, target, reached);
      bridged = true;
    }
  }
  const auto unreached = std::find(reached.begin(), reached.end(), false);
  if (unreached != reached.end()) {
    return MakeError("odometry initialization: vertex " +
                     std::to_string(graph.nodes[static_cast<std::size_t>(unreached - reached.begin())].id) +
                     " is not connected to vertex " + std::to_string(graph.nodes[0].id));
  }
  return Status::Ok();
}

Status InitializeChordal(PoseGraph& graph) {
  if (graph.nodes.size() < 2) return Status::Ok();
  // Any consistent heading assignment unwraps the edges; the odometry one is at hand.
  PoseGraph reference = graph;
  if (Status s = InitializeFromOdometry(reference); !s) return s;
  std::vector<double> chain_heading(graph.nodes.size());
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    chain_heading[n] = reference.nodes[n].estimate.theta();
  }
  const std::size_t edges = graph.betweens.size();
  std::vector<double> kappa(edges);
  std::vector<double> tau(edges);
  Eigen::MatrixXd heading_delta(static_cast<Eigen::Index>(edges), 1);
  for (std::size_t e = 0; e < edges; ++e) {
    const BetweenFactor& f = graph.betweens[e];
    const SeSyncWeights w = SeSyncWeightsOf(f.information);
    kappa[e] = w.kappa;
    tau[e] = w.tau;
    const double z = f.measurement.theta();
    const double turns = std::round((chain_heading[f.to] - chain_heading[f.from] - z) /
                                    (2.0 * std::numbers::pi));
    heading_delta(static_cast<Eigen::Index>(e), 0) = z + 2.0 * std::numbers::pi * turns;
  }
  const Se2 anchor = graph.nodes.front().estimate;
  const std::vector<EdgeEnds> ends = EdgeEndsOf(graph);
  const Result<Eigen::MatrixXd> headings = SolveAnchoredLaplacian(
      graph.nodes.size(), ends, kappa, heading_delta, Eigen::RowVectorXd::Constant(1, chain_heading.front()));
  if (!headings) return headings.error();
  auto heading_of = [&](std::size_t n) {
    return n == 0 ? anchor.theta() : (*headings)(static_cast<Eigen::Index>(n - 1), 0);
  };
  Eigen::MatrixXd translation_delta(static_cast<Eigen::Index>(edges), 2);
  for (std::size_t e = 0; e < edges; ++e) {
    const BetweenFactor& f = graph.betweens[e];
    const Se2 rotation_i(0.0, 0.0, heading_of(f.from));
    translation_delta.row(static_cast<Eigen::Index>(e)) =
        (rotation_i.Rotation() * f.measurement.translation()).transpose();
  }
  const Result<Eigen::MatrixXd> positions =
      SolveAnchoredLaplacian(graph.nodes.size(), ends, tau, translation_delta,
                             anchor.translation().transpose());
  if (!positions) return positions.error();
  for (std::size_t n = 1; n < graph.nodes.size(); ++n) {
    const auto row = static_cast<Eigen::Index>(n - 1);
    graph.nodes[n].estimate = Se2((*positions)(row, 0), (*positions)(row, 1), heading_of(n));
  }
  return Status::Ok();
}

Status Initialize(PoseGraph& graph, Initialization init) { return InitializeBy(graph, init); }

}  // namespace flat2d::localization::graph
