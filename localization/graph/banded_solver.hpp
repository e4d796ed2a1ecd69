// Block-banded Cholesky for the Gauss-Newton systems of a sliding-window pose graph.
//
// With nodes in time order and between factors spanning at most `bandwidth` nodes, the
// information matrix H (thesis 3.4.2, Eq. 3.72) has 3x3 blocks H(k, j) that vanish for
// |k - j| > bandwidth. Its Cholesky factor L (H = L L^T) keeps the same band, so it costs
// O(n bandwidth^2) block products instead of O(n^3):
//   L(k, j) = (H(k, j) - sum_{m < j} L(k, m) L(j, m)^T) L(j, j)^-T,   k - bandwidth <= j < k
//   L(k, k) = chol(H(k, k) - sum_{m < k} L(k, m) L(k, m)^T)                              (B1)
// then H dx = -b by a forward and a backward block substitution (B2). The newest node is
// ordered last, so its marginal covariance is just the last diagonal block of H^-1:
//   (H^-1)(n, n) = (L(n, n) L(n, n)^T)^-1 = L(n, n)^-T L(n, n)^-1                     (B3)
// (L^-1 is lower triangular, so its last column has the single block L(n, n)^-1).
// Only the inverses L(k, k)^-1 of the diagonal blocks are stored: B1 and B2 then need
// only fixed-size 3x3 products.
// Levenberg-Marquardt damping scales the diagonal: H(k, k) + lambda diag(H(k, k)).
// All storage is sized in the constructor for the largest window; nothing allocates after.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace flat2d::localization::graph {

class BlockBandedSystem {
 public:
  // Room for up to `max_blocks` 3x3 diagonal blocks and `bandwidth` >= 1 sub-diagonals.
  BlockBandedSystem(int max_blocks, int bandwidth);

  int bandwidth() const { return bandwidth_; }
  int size() const { return size_; }

  // Zeroes H and b of the first `blocks` blocks (<= max_blocks) and makes that the size.
  void Reset(int blocks);

  // H(k, k) += block.
  void AddDiagonal(int k, const Eigen::Matrix3d& block);
  // H(row, col) += block (and H(col, row) += block^T), 0 < row - col <= bandwidth.
  void AddOffDiagonal(int row, int col, const Eigen::Matrix3d& block);
  // b(k) += gradient, b = sum J^T Omega e (thesis Eq. 3.73).
  void AddGradient(int k, const Eigen::Vector3d& gradient);

  // B1 on H + lambda diag(H); false when that matrix is not positive definite.
  bool Factorize(double lambda);
  // B2: the step dx of (H + lambda diag(H)) dx = -b with the last factorization.
  void SolveStep();
  const Eigen::Vector3d& Step(int k) const { return step_[Index(k)]; }

  // B3: the covariance of the last block from the last factorization.
  Eigen::Matrix3d LastBlockCovariance() const;

 private:
  static std::size_t Index(int k) { return static_cast<std::size_t>(k); }
  std::size_t OffIndex(int row, int distance) const {
    return static_cast<std::size_t>(row * bandwidth_ + distance - 1);
  }

  int max_blocks_;
  int bandwidth_;
  int size_ = 0;
  std::vector<Eigen::Matrix3d> h_diagonal_;   // max_blocks
  std::vector<Eigen::Matrix3d> h_band_;       // max_blocks x bandwidth: H(k, k - d)
  std::vector<Eigen::Vector3d> gradient_;     // max_blocks
  std::vector<Eigen::Matrix3d> l_inverse_;    // max_blocks: L(k, k)^-1, lower triangular
  std::vector<Eigen::Matrix3d> l_band_;       // max_blocks x bandwidth: L(k, k - d)
  std::vector<Eigen::Vector3d> step_;         // max_blocks; forward result, then the step
};

}  // namespace flat2d::localization::graph
