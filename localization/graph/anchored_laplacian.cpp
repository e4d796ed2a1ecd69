#include "localization/graph/anchored_laplacian.hpp"

#include <Eigen/SparseCholesky>
#include <vector>

namespace flat2d::localization::graph {

Result<Eigen::MatrixXd> SolveAnchoredLaplacian(std::size_t node_count, std::span<const EdgeEnds> edges,
                                               std::span<const double> weights,
                                               const Eigen::MatrixXd& deltas,
                                               const Eigen::RowVectorXd& anchor) {
  const auto n = static_cast<Eigen::Index>(node_count);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n - 1, deltas.cols());
  auto add = [&](Eigen::Index r, Eigen::Index c, double v) {
    if (r > 0 && c > 0) triplets.emplace_back(r - 1, c - 1, v);
  };
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto i = static_cast<Eigen::Index>(edges[e].from);
    const auto j = static_cast<Eigen::Index>(edges[e].to);
    const double w = weights[e];
    add(i, i, w);
    add(j, j, w);
    add(i, j, -w);
    add(j, i, -w);
    const Eigen::RowVectorXd d = deltas.row(static_cast<Eigen::Index>(e));
    if (j > 0) rhs.row(j - 1) += w * d;
    if (i > 0) rhs.row(i - 1) -= w * d;
    if (i == 0 && j > 0) rhs.row(j - 1) += w * anchor;  // v_0 moved to the right-hand side
    if (j == 0 && i > 0) rhs.row(i - 1) += w * anchor;
  }
  Eigen::SparseMatrix<double> laplacian(n - 1, n - 1);
  laplacian.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(laplacian);
  if (ldlt.info() != Eigen::Success) return MakeError("chordal initialization: singular system");
  return Eigen::MatrixXd(ldlt.solve(rhs));
}

}  // namespace flat2d::localization::graph
