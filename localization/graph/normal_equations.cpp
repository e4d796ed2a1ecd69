#include "localization/graph/normal_equations.hpp"

#include <algorithm>
#include <cassert>

namespace flat2d::localization::graph {
namespace {

// Max-mixture between factors use F2 with the wrapped angle, like g2o's edges.
constexpr AngleResidual kMixtureAngle = AngleResidual::kWrapped;

}  // namespace

NormalEquations::NormalEquations(const PoseGraph& graph) : graph_(graph) {
  block_of_node_.assign(graph.nodes.size(), -1);
  int blocks = 0;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    if (!graph.nodes[n].fixed) block_of_node_[n] = blocks++;
  }
  gradient_ = Eigen::VectorXd::Zero(3 * blocks);
  BuildPattern();
}

void NormalEquations::BuildPattern() {
  const int size = static_cast<int>(gradient_.size());
  std::vector<Eigen::Triplet<double>> triplets;
  auto mark = [&](int row_block, int col_block) {
    if (row_block < 0 || col_block < 0) return;
    if (row_block < col_block) std::swap(row_block, col_block);
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) triplets.emplace_back(3 * row_block + r, 3 * col_block + c, 0.0);
    }
  };
  for (int b = 0; b < size / 3; ++b) mark(b, b);
  for (const BetweenFactor& f : graph_.betweens) mark(block_of_node_[f.from], block_of_node_[f.to]);
  for (const MaxMixtureBetweenFactor& f : graph_.mixture_betweens) {
    mark(block_of_node_[f.from], block_of_node_[f.to]);
  }
  hessian_.resize(size, size);
  hessian_.setFromTriplets(triplets.begin(), triplets.end());  // duplicates summed: still 0
  hessian_.makeCompressed();

  diagonal_slots_.resize(static_cast<std::size_t>(size));
  for (int b = 0; b < size / 3; ++b) {
    const BlockSlot slot = SlotOf(b, b);
    for (int k = 0; k < 3; ++k) diagonal_slots_[static_cast<std::size_t>(3 * b + k)] = slot[k] + k;
  }
  for (const BetweenFactor& f : graph_.betweens) {
    between_slots_.push_back(SlotsFor(block_of_node_[f.from], block_of_node_[f.to]));
  }
  for (const PriorFactor& f : graph_.priors) {
    prior_slots_.push_back(SlotsFor(block_of_node_[f.node], -1));
  }
  for (const MaxMixtureBetweenFactor& f : graph_.mixture_betweens) {
    mixture_between_slots_.push_back(SlotsFor(block_of_node_[f.from], block_of_node_[f.to]));
  }
  for (const MaxMixturePriorFactor& f : graph_.mixture_priors) {
    mixture_prior_slots_.push_back(SlotsFor(block_of_node_[f.node], -1));
  }
}

NormalEquations::BlockSlot NormalEquations::SlotOf(int row_block, int col_block) const {
  BlockSlot slot{};
  for (int c = 0; c < 3; ++c) {
    const int column = 3 * col_block + c;
    const int* begin = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[column];
    const int* end = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[column + 1];
    const int* found = std::lower_bound(begin, end, 3 * row_block);
    assert(found != end && *found == 3 * row_block);
    slot[static_cast<std::size_t>(c)] = static_cast<int>(found - hessian_.innerIndexPtr());
  }
  return slot;
}

NormalEquations::FactorSlots NormalEquations::SlotsFor(int block_i, int block_j) const {
  FactorSlots slots;
  slots.block_i = block_i;
  slots.block_j = block_j;
  if (block_i >= 0) slots.ii = SlotOf(block_i, block_i);
  if (block_j >= 0) slots.jj = SlotOf(block_j, block_j);
  if (block_i >= 0 && block_j >= 0 && block_i != block_j) {
    slots.ij = SlotOf(std::max(block_i, block_j), std::min(block_i, block_j));
  }
  return slots;
}

void NormalEquations::AddBlock(const BlockSlot& slot, const Eigen::Matrix3d& value) {
  double* values = hessian_.valuePtr();
  for (int c = 0; c < 3; ++c) {
    double* column = values + slot[static_cast<std::size_t>(c)];
    for (int r = 0; r < 3; ++r) column[r] += value(r, c);
  }
}

void NormalEquations::AddBinary(const FactorSlots& slots, const Eigen::Matrix3d& jacobian_i,
                                const Eigen::Matrix3d& jacobian_j,
                                const Eigen::Matrix3d& information, const Eigen::Vector3d& error) {
  const Eigen::Matrix3d jt_l_i = jacobian_i.transpose() * information;
  const Eigen::Matrix3d jt_l_j = jacobian_j.transpose() * information;
  if (slots.block_i >= 0) {
    AddBlock(slots.ii, jt_l_i * jacobian_i);
    gradient_.segment<3>(3 * slots.block_i) += jt_l_i * error;
  }
  if (slots.block_j >= 0) {
    AddBlock(slots.jj, jt_l_j * jacobian_j);
    gradient_.segment<3>(3 * slots.block_j) += jt_l_j * error;
  }
  if (slots.block_i >= 0 && slots.block_j >= 0 && slots.block_i != slots.block_j) {
    // The stored block is the lower one: rows of the larger block index.
    if (slots.block_i > slots.block_j) {
      AddBlock(slots.ij, jt_l_i * jacobian_j);
    } else {
      AddBlock(slots.ij, jt_l_j * jacobian_i);
    }
  }
}

void NormalEquations::AddUnary(const FactorSlots& slots, const Eigen::Matrix3d& information,
                               const Eigen::Vector3d& error) {
  if (slots.block_i < 0) return;
  AddBlock(slots.ii, information);  // F4: J = I
  gradient_.segment<3>(3 * slots.block_i) += information * error;
}

double NormalEquations::Linearize(std::span<const Se2> estimates) {
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  gradient_.setZero();
  double cost = 0.0;
  for (std::size_t k = 0; k < graph_.betweens.size(); ++k) {
    const BetweenFactor& f = graph_.betweens[k];
    const BetweenLinearization lin =
        LinearizeBetween(estimates[f.from], estimates[f.to], f.measurement, f.angle);
    AddBinary(between_slots_[k], lin.jacobian_i, lin.jacobian_j, f.information, lin.error);
    cost += lin.error.dot(f.information * lin.error);
  }
  for (std::size_t k = 0; k < graph_.priors.size(); ++k) {
    const PriorFactor& f = graph_.priors[k];
    const Eigen::Vector3d error = PriorError(estimates[f.node], f.measurement);
    AddUnary(prior_slots_[k], f.information, error);
    cost += error.dot(f.information * error);
  }
  for (std::size_t k = 0; k < graph_.mixture_betweens.size(); ++k) {
    const MaxMixtureBetweenFactor& f = graph_.mixture_betweens[k];
    const BetweenLinearization lin =
        LinearizeBetween(estimates[f.from], estimates[f.to], f.measurement, kMixtureAngle);
    const MixtureChoice choice = SelectMixtureComponent(f.mixture, lin.error);
    AddBinary(mixture_between_slots_[k], lin.jacobian_i, lin.jacobian_j, choice.information,
              lin.error);
    cost += choice.cost;
  }
  for (std::size_t k = 0; k < graph_.mixture_priors.size(); ++k) {
    const MaxMixturePriorFactor& f = graph_.mixture_priors[k];
    const Eigen::Vector3d error = PriorError(estimates[f.node], f.measurement);
    const MixtureChoice choice = SelectMixtureComponent(f.mixture, error);
    AddUnary(mixture_prior_slots_[k], choice.information, error);
    cost += choice.cost;
  }
  return cost;
}

double NormalEquations::Cost(std::span<const Se2> estimates) const {
  double cost = 0.0;
  for (const BetweenFactor& f : graph_.betweens) {
    const Eigen::Vector3d e = BetweenError(estimates[f.from], estimates[f.to], f.measurement, f.angle);
    cost += e.dot(f.information * e);
  }
  for (const PriorFactor& f : graph_.priors) {
    const Eigen::Vector3d e = PriorError(estimates[f.node], f.measurement);
    cost += e.dot(f.information * e);
  }
  for (const MaxMixtureBetweenFactor& f : graph_.mixture_betweens) {
    const Eigen::Vector3d e =
        BetweenError(estimates[f.from], estimates[f.to], f.measurement, kMixtureAngle);
    cost += SelectMixtureComponent(f.mixture, e).cost;
  }
  for (const MaxMixturePriorFactor& f : graph_.mixture_priors) {
    cost += SelectMixtureComponent(f.mixture, PriorError(estimates[f.node], f.measurement)).cost;
  }
  return cost;
}

void NormalEquations::AddToDiagonal(double lambda) {
  double* values = hessian_.valuePtr();
  for (const int slot : diagonal_slots_) values[slot] += lambda;
}

double NormalEquations::MaxDiagonal() const {
  double max_value = 0.0;
  for (const int slot : diagonal_slots_) max_value = std::max(max_value, hessian_.valuePtr()[slot]);
  return max_value;
}

}  // namespace flat2d::localization::graph
