// Initial estimates for a pose graph whose file has none (or whose values are not wanted).
//  - Odometry chain: node 0 keeps its estimate; node k = node k-1 composed with the between
//    factor k-1 -> k (or the inverse of k -> k-1); where the chain breaks (ais2klinik), any
//    edge from a reached node bridges to the next chain segment. This is the start the acceptance tests
//    use, and the hard one: drift grows along the chain.
//  - Chordal / LAGO-style (Carlone et al., "A fast and accurate approximation for planar
//    pose graph optimization", IJRR 2014): (1) orientations by linear least squares over
//    theta_j - theta_i = z_theta + 2 pi k, with k unwrapping each edge against the
//    odometry-chain orientations (any consistent assignment works: a tree edge gets
//    exactly the reference difference); (2) positions by linear least squares over
//    t_j - t_i = R(theta_i) z_t with those orientations. Node 0 anchors both.
#pragma once

#include <algorithm>
#include <string_view>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

enum class Initialization { kFile, kOdometry, kChordal };
std::string_view InitializationName(Initialization init);

// Errors when some node is not connected to node 0.
Status InitializeFromOdometry(PoseGraph& graph);
// Errors as InitializeFromOdometry, or when a linear system is singular.
Status InitializeChordal(PoseGraph& graph);

// kFile keeps the file's values when every node has one, else falls back to the odometry
// chain (the file has none, e.g. manhattan.g2o).
Status Initialize(PoseGraph& graph, Initialization init);

// That dispatch for any graph whose nodes carry `has_estimate` and which has its own
// InitializeFromOdometry and InitializeChordal (found by argument-dependent lookup).
template <typename Graph>
Status InitializeBy(Graph& graph, Initialization init) {
  const bool file_has_all = std::all_of(graph.nodes.begin(), graph.nodes.end(),
                                        [](const auto& node) { return node.has_estimate; });
  switch (init) {
    case Initialization::kFile:
      return file_has_all ? Status::Ok() : InitializeFromOdometry(graph);
    case Initialization::kOdometry: return InitializeFromOdometry(graph);
    case Initialization::kChordal: return InitializeChordal(graph);
  }
  return Status::Ok();
}

}  // namespace flat2d::localization::graph
