// The Gauss-Newton normal equations H dx = -b of a pose graph (thesis 3.4.2, Alg. 6 lines
// 3-10), in a sparse matrix whose pattern is built once and whose values are refilled in
// place at every linearization: the optimizer's iterations then allocate nothing and the
// symbolic factorization (AMD ordering) is reused.
//
// Steps: (1) give every free node a 3x3 block (fixed nodes get none; they only enter through
// the error); (2) from the factors, mark the blocks of H that can be non-zero - the diagonal
// blocks whole, the off-diagonal blocks in the lower triangle only, which is what
// SimplicialLDLT<Lower> reads - and remember where each factor's blocks live in the value
// array; (3) per linearization, zero the values and add J_a^T L J_b and J_a^T L e.
//
// Max-mixture between factors use F2 with the wrapped angle whatever the other factors use.
// Costs are sum e^T L e (+ F5 offsets for max-mixtures) with no factor 1/2, matching both
// conventions of REFERENCE_RESULTS.md; H = sum J^T L J and b = sum J^T L e, so a step of
// the cost's quadratic model c + 2 b^T dx + dx^T H dx is dx = -H^-1 b.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

class NormalEquations {
 public:
  static constexpr int kBlockSize = 3;  // (x, y, theta) per free node

  explicit NormalEquations(const PoseGraph& graph);

  // Fills H and b at `estimates` (one per node) and returns the cost there.
  double Linearize(std::span<const Se2> estimates);
  // The cost at `estimates`, without linearizing.
  double Cost(std::span<const Se2> estimates) const;

  // Adds `lambda` to (or, with -lambda, removes it from) the diagonal of H (LM damping).
  void AddToDiagonal(double lambda);
  double MaxDiagonal() const;

  // H over the free nodes' blocks; only the lower triangle is meaningful.
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }
  const Eigen::VectorXd& gradient() const { return gradient_; }
  // The block of each node in H, or -1 for fixed nodes.
  const std::vector<int>& block_of_node() const { return block_of_node_; }
  std::size_t variable_count() const { return static_cast<std::size_t>(gradient_.size()); }

 private:
  // Value-array offsets of a 3x3 block's three columns (rows are contiguous within each).
  using BlockSlot = std::array<int, 3>;
  struct FactorSlots {
    int block_i = -1;  // -1: the node is fixed (or absent for unary factors)
    int block_j = -1;
    BlockSlot ii{};
    BlockSlot jj{};
    BlockSlot ij{};  // the lower one of (i, j) and (j, i)
  };

  void BuildPattern();
  BlockSlot SlotOf(int row_block, int col_block) const;
  FactorSlots SlotsFor(int block_i, int block_j) const;
  void AddBlock(const BlockSlot& slot, const Eigen::Matrix3d& value);
  void AddBinary(const FactorSlots& slots, const Eigen::Matrix3d& jacobian_i,
                 const Eigen::Matrix3d& jacobian_j, const Eigen::Matrix3d& information,
                 const Eigen::Vector3d& error);
  void AddUnary(const FactorSlots& slots, const Eigen::Matrix3d& information,
                const Eigen::Vector3d& error);

  const PoseGraph& graph_;
  std::vector<int> block_of_node_;
  Eigen::SparseMatrix<double> hessian_;
  Eigen::VectorXd gradient_;
  std::vector<int> diagonal_slots_;
  std::vector<FactorSlots> between_slots_;
  std::vector<FactorSlots> prior_slots_;
  std::vector<FactorSlots> mixture_between_slots_;
  std::vector<FactorSlots> mixture_prior_slots_;
};

}  // namespace flat2d::localization::graph
