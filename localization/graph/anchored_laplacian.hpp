// The linear least-squares step of chordal initialization (Carlone et al., "A fast and
// accurate approximation for planar pose graph optimization", IJRR 2014; Rosen et al.'s
// chordal start, IJRR 2019 sec. 6), shared by SE(2) and SE(3) graphs: given per-edge
// differences d_e (rows of `deltas`) and weights w_e, find the node values v (rows) that
// minimize sum_e w_e |v_to - v_from - d_e|^2 with node 0 held at `anchor`. The normal
// equations are the weighted graph Laplacian without node 0's row and column, solved by a
// sparse LDL^T for all columns at once.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "hal/common/error.hpp"

namespace flat2d::localization::graph {

struct EdgeEnds {
  std::size_t from = 0;
  std::size_t to = 0;
};

// Rows 1 .. node_count - 1 of the solution (row k - 1 is node k); an error when the system
// is singular (a node not connected to node 0).
Result<Eigen::MatrixXd> SolveAnchoredLaplacian(std::size_t node_count, std::span<const EdgeEnds> edges,
                                               std::span<const double> weights,
                                               const Eigen::MatrixXd& deltas,
                                               const Eigen::RowVectorXd& anchor);

}  // namespace flat2d::localization::graph
