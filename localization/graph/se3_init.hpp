// Initial estimates for an SE(3) pose graph (graph_init.hpp has the SE(2) ones):
//  - Odometry chain: node 0 keeps its estimate; node k = node k-1 composed with the between
//    factor k-1 -> k (or the inverse of k -> k-1); where the chain breaks, any edge from a
//    reached node bridges to the next segment.
//  - Chordal (Carlone et al., "Initialization techniques for 3D SLAM", ICRA 2015): (1) the
//    rotations by linear least squares over R_j = R_i R_z with the nine entries of each R
//    free, weighted by SE-Sync's kappa - row r of R_j equals row r of R_i times R_z, so the
//    three rows are three systems with one matrix; (2) each R projected onto SO(3) by SVD
//    (U diag(1, 1, det(U V^T)) V^T); (3) the positions by linear least squares over
//    t_j - t_i = R_i t_z with those rotations, weighted by tau (anchored_laplacian.hpp).
//    Node 0 anchors both steps at its current estimate.
#pragma once

#include "hal/common/error.hpp"
#include "localization/graph/graph_init.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

// Errors when some node is not connected to node 0.
Status InitializeFromOdometry(Se3PoseGraph& graph);
// Errors when a linear system is singular (a node not connected to node 0).
Status InitializeChordal(Se3PoseGraph& graph);

// kFile keeps the file's values when every node has one, else falls back to the odometry
// chain.
Status Initialize(Se3PoseGraph& graph, Initialization init);

}  // namespace flat2d::localization::graph
