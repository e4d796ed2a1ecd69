// The Gauss-Newton normal equations H dx = -b of an SE(3) pose graph (thesis 3.4.2, Alg. 6
// lines 3-10), the 6x6-block counterpart of normal_equations.hpp: a sparse matrix whose
// pattern is built once and whose values are refilled in place at every linearization, so
// the optimizer's iterations allocate nothing and the AMD ordering is analysed once.
//
// Steps: (1) give every free node a 6x6 block (fixed nodes get none); (2) mark the blocks of
// H the factors touch - diagonal blocks whole, off-diagonal ones in the lower triangle only,
// which SimplicialLDLT<Lower> reads - and remember each factor's slots in the value array;
// (3) per linearization, add each factor's J_a^T L J_b and J_a^T L e (se3_factors.hpp, G2
// and G3). L is used as given, not through a square root, since some published files
// (cubicle) carry indefinite information matrices that g2o and SE-Sync read as they are.
// Costs have no factor 1/2 (REFERENCE_RESULTS.md): H = sum J^T L J, b = sum J^T L e, and a
// step of the model c + 2 b^T dx + dx^T H dx is dx = -H^-1 b.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <array>
#include <span>
#include <vector>

#include "localization/graph/se3_factors.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

class Se3NormalEquations {
 public:
  static constexpr int kBlockSize = 6;  // (dt, w) per free node, G1

  explicit Se3NormalEquations(const Se3PoseGraph& graph);

  // Fills H and b at `estimates` (one per node) and returns the cost there.
  double Linearize(std::span<const Eigen::Isometry3d> estimates);
  // The cost at `estimates`, without linearizing.
  double Cost(std::span<const Eigen::Isometry3d> estimates) const;

  // Adds `lambda` to (or, with -lambda, removes it from) the diagonal of H (LM damping).
  void AddToDiagonal(double lambda);
  double MaxDiagonal() const;

  // H over the free nodes' blocks; only the lower triangle is meaningful.
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }
  const Eigen::VectorXd& gradient() const { return gradient_; }
  // The block of each node in H, or -1 for fixed nodes.
  const std::vector<int>& block_of_node() const { return block_of_node_; }

 private:
  // Value-array offsets of a 6x6 block's columns (rows are contiguous within each).
  using BlockSlot = std::array<int, kBlockSize>;
  struct FactorSlots {
    int block_i = -1;  // -1: the node is fixed
    int block_j = -1;
    BlockSlot ii{};
    BlockSlot jj{};
    BlockSlot ij{};  // the lower one of (i, j) and (j, i)
  };

  void BuildPattern();
  BlockSlot SlotOf(int row_block, int col_block) const;
  void AddBlock(const BlockSlot& slot, const Matrix6d& value);
  void AddBinary(const FactorSlots& slots, const Se3BetweenLinearization& lin,
                 const Matrix6d& information);

  const Se3PoseGraph& graph_;
  std::vector<int> block_of_node_;
  Eigen::SparseMatrix<double> hessian_;
  Eigen::VectorXd gradient_;
  std::vector<int> diagonal_slots_;
  std::vector<FactorSlots> between_slots_;
};

}  // namespace flat2d::localization::graph
