// The Gaussian prior that marginalizing a sliding window's oldest node leaves on the nodes
// it was connected to (Schur complement of the Gauss-Newton system, thesis 3.4.2).
//
// When the oldest node o leaves the window, every factor touching it (its unary factors, its
// between factors to the next <= B nodes, and the previous prior) is linearized at the
// current estimate x-bar. In the increments delta of the component retraction (F1 of
// se2_factors.hpp) their chi-square is the quadratic
//   F(delta) = c + 2 b^T delta + delta^T H delta,  H = sum J^T Omega J, b = sum J^T Omega e
// over (o, K), K = the B nodes after o. Minimizing over delta_o (exact for a quadratic):
//   H' = H_KK - H_Ko H_oo^-1 H_oK,  b' = b_K - H_Ko H_oo^-1 b_o,  c' = c - b_o^T H_oo^-1 b_o  (M1)
// (H_oo^-1 a pseudo-inverse when o carried no information). The prior keeps its
// linearization point x-bar_K and is evaluated later at delta_k = x_k [-] x-bar_k, the
// component difference. With F1 that difference is exactly the increment, so the prior's
// Jacobian is the identity and re-expressing it at a new estimate is exact:
//   cost = c' + 2 b'^T delta + delta^T H' delta,  gradient b' + H' delta,  Hessian H'.   (M2)
// Consistency choice: H' and b' are never re-linearized (first-estimate Jacobians): the
// information about the marginalized past is frozen at the estimate it had when it left,
// so later solves cannot make the window over-confident by relinearizing it. When the next
// node leaves, the prior is folded in through M2 at the then current estimate, and M1
// produces a prior over the next B nodes, so a prior never covers more than B nodes.
#pragma once

#include <Eigen/Core>
#include <array>

#include "localization/odometry/se2.hpp"

namespace flat2d::localization::graph {

// The largest node distance of a between factor, B (sizes the fixed-size prior below).
inline constexpr int kMaxBetweenSpan = 4;

// A dense matrix of at most 3 (B + 1) rows on the stack: the local marginalization system.
using LocalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                  3 * (kMaxBetweenSpan + 1), 3 * (kMaxBetweenSpan + 1)>;
using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * (kMaxBetweenSpan + 1), 1>;

// M2's prior over the window's first `size` nodes.
struct MarginalPrior {
  int size = 0;  // 0: no prior yet
  std::array<Se2, kMaxBetweenSpan> linearization{};
  LocalMatrix information;  // H', 3 size x 3 size
  LocalVector gradient;     // b'
  double constant = 0.0;    // c'
};

// The increments delta_k = x_k [-] x-bar_k of the prior's nodes; `estimates` holds at
// least prior.size poses, the window's oldest first.
LocalVector PriorIncrement(const MarginalPrior& prior, const Se2* estimates);

// M2's chi-square at delta.
double PriorCost(const MarginalPrior& prior, const LocalVector& delta);

// M1: eliminates the first node (3 rows) of the local system (h, b, c) over 1 + kept
// nodes; the result is the prior over the kept nodes, linearized at `kept_estimates`.
MarginalPrior EliminateFirstNode(const LocalMatrix& h, const LocalVector& b, double c,
                                 const Se2* kept_estimates, int kept);

}  // namespace flat2d::localization::graph
