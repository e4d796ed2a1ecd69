#include "localization/graph/se3_normal_equations.hpp"

#include <algorithm>
#include <cassert>

#include "localization/graph/se3_costs.hpp"

namespace flat2d::localization::graph {
namespace {

constexpr int kB = Se3NormalEquations::kBlockSize;

}  // namespace

Se3NormalEquations::Se3NormalEquations(const Se3PoseGraph& graph) : graph_(graph) {
  block_of_node_.assign(graph.nodes.size(), -1);
  int blocks = 0;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    if (!graph.nodes[n].fixed) block_of_node_[n] = blocks++;
  }
  gradient_ = Eigen::VectorXd::Zero(kB * blocks);
  BuildPattern();
}

void Se3NormalEquations::BuildPattern() {
  const int size = static_cast<int>(gradient_.size());
  std::vector<Eigen::Triplet<double>> triplets;
  auto mark = [&](int row_block, int col_block) {
    if (row_block < 0 || col_block < 0) return;
    if (row_block < col_block) std::swap(row_block, col_block);
    for (int c = 0; c < kB; ++c) {
      for (int r = 0; r < kB; ++r) triplets.emplace_back(kB * row_block + r, kB * col_block + c, 0.0);
    }
  };
  for (int b = 0; b < size / kB; ++b) mark(b, b);
  for (const Se3BetweenFactor& f : graph_.betweens) mark(block_of_node_[f.from], block_of_node_[f.to]);
  hessian_.resize(size, size);
  hessian_.setFromTriplets(triplets.begin(), triplets.end());  // duplicates summed: still 0
  hessian_.makeCompressed();

  diagonal_slots_.resize(static_cast<std::size_t>(size));
  for (int b = 0; b < size / kB; ++b) {
    const BlockSlot slot = SlotOf(b, b);
    for (int k = 0; k < kB; ++k) diagonal_slots_[static_cast<std::size_t>(kB * b + k)] = slot[k] + k;
  }
  between_slots_.reserve(graph_.betweens.size());
  for (const Se3BetweenFactor& f : graph_.betweens) {
    FactorSlots slots;
    slots.block_i = block_of_node_[f.from];
    slots.block_j = block_of_node_[f.to];
    if (slots.block_i >= 0) slots.ii = SlotOf(slots.block_i, slots.block_i);
    if (slots.block_j >= 0) slots.jj = SlotOf(slots.block_j, slots.block_j);
    if (slots.block_i >= 0 && slots.block_j >= 0) {
      slots.ij = SlotOf(std::max(slots.block_i, slots.block_j), std::min(slots.block_i, slots.block_j));
    }
    between_slots_.push_back(slots);
  }
}

Se3NormalEquations::BlockSlot Se3NormalEquations::SlotOf(int row_block, int col_block) const {
  BlockSlot slot{};
  for (int c = 0; c < kB; ++c) {
    const int column = kB * col_block + c;
    const int* begin = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[column];
    const int* end = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[column + 1];
    const int* found = std::lower_bound(begin, end, kB * row_block);
    assert(found != end && *found == kB * row_block);
    slot[static_cast<std::size_t>(c)] = static_cast<int>(found - hessian_.innerIndexPtr());
  }
  return slot;
}

void Se3NormalEquations::AddBlock(const BlockSlot& slot, const Matrix6d& value) {
  double* values = hessian_.valuePtr();
  for (int c = 0; c < kB; ++c) {
    double* column = values + slot[static_cast<std::size_t>(c)];
    for (int r = 0; r < kB; ++r) column[r] += value(r, c);
  }
}

void Se3NormalEquations::AddBinary(const FactorSlots& slots, const Se3BetweenLinearization& lin,
                                   const Matrix6d& information) {
  const Matrix6d jt_l_i = lin.jacobian_i.transpose() * information;
  const Matrix6d jt_l_j = lin.jacobian_j.transpose() * information;
  if (slots.block_i >= 0) {
    AddBlock(slots.ii, jt_l_i * lin.jacobian_i);
    gradient_.segment<kB>(kB * slots.block_i) += jt_l_i * lin.error;
  }
  if (slots.block_j >= 0) {
    AddBlock(slots.jj, jt_l_j * lin.jacobian_j);
    gradient_.segment<kB>(kB * slots.block_j) += jt_l_j * lin.error;
  }
  if (slots.block_i >= 0 && slots.block_j >= 0) {
    // The stored block is the lower one: rows of the larger block index.
    if (slots.block_i > slots.block_j) {
      AddBlock(slots.ij, jt_l_i * lin.jacobian_j);
    } else {
      AddBlock(slots.ij, jt_l_j * lin.jacobian_i);
    }
  }
}

double Se3NormalEquations::Linearize(std::span<const Eigen::Isometry3d> estimates) {
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  gradient_.setZero();
  double cost = 0.0;
  for (std::size_t k = 0; k < graph_.betweens.size(); ++k) {
    const Se3BetweenFactor& f = graph_.betweens[k];
    const Se3BetweenLinearization lin =
        LinearizeSe3Between(estimates[f.from], estimates[f.to], f.measurement);
    AddBinary(between_slots_[k], lin, f.information);
    cost += lin.error.dot(f.information * lin.error);
  }
  return cost;
}

double Se3NormalEquations::Cost(std::span<const Eigen::Isometry3d> estimates) const {
  double cost = 0.0;
  for (const Se3BetweenFactor& f : graph_.betweens) {
    cost += BetweenCost(f, estimates[f.from], estimates[f.to]);
  }
  return cost;
}

void Se3NormalEquations::AddToDiagonal(double lambda) {
  double* values = hessian_.valuePtr();
  for (const int slot : diagonal_slots_) values[slot] += lambda;
}

double Se3NormalEquations::MaxDiagonal() const {
  double max_value = 0.0;
  for (const int slot : diagonal_slots_) max_value = std::max(max_value, hessian_.valuePtr()[slot]);
  return max_value;
}

}  // namespace flat2d::localization::graph
