// SlidingWindowGraph's linearization, Gauss-Newton / Levenberg-Marquardt loop and
// marginalization of the oldest node (the steps are in sliding_window.hpp).
#include <algorithm>
#include <cmath>

#include "localization/graph/sliding_window.hpp"

namespace flat2d::localization::graph {
namespace {

// Levenberg-Marquardt: the first damping after a rejected step, its growth and decay, the
// damping below which it is switched off again (plain Gauss-Newton).
constexpr double kInitialDamping = 1e-4;
constexpr double kDampingGrowth = 10.0;
constexpr double kDampingDecay = 0.1;
constexpr double kNoDampingBelow = 1e-8;
// A step is accepted unless it raises the cost by more than this relative amount
// (rounding in a cost of ~1e3 terms).
constexpr double kCostTolerance = 1e-12;

void AddUnaryTerm(const Eigen::Matrix3d& information, const Eigen::Vector3d& error, int at,
                  BlockBandedSystem& system) {
  // F4: the Jacobian is the identity.
  system.AddDiagonal(at, information);
  system.AddGradient(at, information * error);
}

void AddBetweenTerm(const BetweenLinearization& lin, const Eigen::Matrix3d& information, int from,
                    int to, BlockBandedSystem& system) {
  const Eigen::Matrix3d omega_a = information * lin.jacobian_i;
  const Eigen::Matrix3d omega_b = information * lin.jacobian_j;
  system.AddDiagonal(from, lin.jacobian_i.transpose() * omega_a);
  system.AddDiagonal(to, lin.jacobian_j.transpose() * omega_b);
  system.AddOffDiagonal(to, from, lin.jacobian_j.transpose() * omega_a);
  system.AddGradient(from, omega_a.transpose() * lin.error);
  system.AddGradient(to, omega_b.transpose() * lin.error);
}

}  // namespace

double SlidingWindowGraph::Assemble() {
  system_.Reset(size_);
  double cost = 0.0;
  for (int p = 0; p < size_; ++p) {
    const Node& node = nodes_[Slot(p)];
    const Se2& x = estimates_[static_cast<std::size_t>(p)];
    for (int k = 0; k < node.unary_count; ++k) {
      UnaryFactor& factor = Unary(p, k);
      const Eigen::Vector3d error = PriorError(x, factor.measurement);
      const MixtureChoice choice = SelectMixtureComponent(factor.mixture, error);  // F5
      factor.component = choice.component;
      cost += choice.cost;
      AddUnaryTerm(choice.information, error, p, system_);
    }
    for (int k = 0; k < node.between_count; ++k) {
      const BetweenFactor& factor = Between(p, k);
      const int to = p + factor.span;
      const BetweenLinearization lin =
          LinearizeBetween(x, estimates_[static_cast<std::size_t>(to)], factor.measurement);
      cost += lin.error.dot(factor.information * lin.error);
      AddBetweenTerm(lin, factor.information, p, to, system_);
    }
  }
  if (prior_.size > 0) {  // M2
    const LocalVector delta = PriorIncrement(prior_, estimates_.data());
    cost += PriorCost(prior_, delta);
    const LocalVector gradient = prior_.gradient + prior_.information * delta;
    for (int a = 0; a < prior_.size; ++a) {
      system_.AddGradient(a, gradient.segment<3>(3 * a));
      system_.AddDiagonal(a, prior_.information.block<3, 3>(3 * a, 3 * a));
      for (int b = 0; b < a; ++b) {
        system_.AddOffDiagonal(a, b, prior_.information.block<3, 3>(3 * a, 3 * b));
      }
    }
  }
  return cost;
}

Result<WindowSolution> SlidingWindowGraph::Solve(int max_iterations) {
  if (size_ == 0) return MakeError("the window is empty");
  if (max_iterations < 0) return MakeError("max_iterations must be >= 0");
  const auto window = static_cast<std::ptrdiff_t>(size_);
  std::copy(estimates_.begin(), estimates_.begin() + window, backup_.begin());
  WindowSolution solution;
  double cost = Assemble();
  solution.initial_cost = cost;
  // Anchoring is structural: without a unary factor reaching every node H stays singular.
  if (!std::isfinite(cost) || !system_.Factorize(0.0)) {
    return MakeError("the window is not anchored: add a prior or a match");
  }
  bool factorized = true;  // the undamped factorization above serves the first step
  double damping = 0.0;
  while (solution.iterations < max_iterations && !solution.converged) {
    ++solution.iterations;
    if (!factorized && !system_.Factorize(damping)) {
      damping = std::max(kInitialDamping, damping * kDampingGrowth);
      continue;
    }
    factorized = false;
    system_.SolveStep();
    double largest_step = 0.0;
    for (int p = 0; p < size_; ++p) {
      Se2& x = estimates_[static_cast<std::size_t>(p)];
      largest_step = std::max(largest_step, system_.Step(p).cwiseAbs().maxCoeff());
      x = Retract(x, system_.Step(p));  // F1
    }
    const double new_cost = Assemble();
    if (!options_.levenberg_marquardt || new_cost <= cost * (1.0 + kCostTolerance)) {
      solution.converged = largest_step < options_.step_tolerance;
      cost = new_cost;
      std::copy(estimates_.begin(), estimates_.begin() + window, backup_.begin());
      damping = damping * kDampingDecay < kNoDampingBelow ? 0.0 : damping * kDampingDecay;
    } else {  // rejected: back to the last accepted estimate, damp harder
      std::copy(backup_.begin(), backup_.begin() + window, estimates_.begin());
      cost = Assemble();
      damping = std::max(kInitialDamping, damping * kDampingGrowth);
    }
  }
  // B3 at the final estimate, without damping.
  if (!system_.Factorize(0.0)) {
    return MakeError("the information matrix at the solution is not positive definite");
  }
  solution.final_cost = cost;
  solution.newest = newest_id();
  solution.newest_global_T_vehicle = estimates_[static_cast<std::size_t>(size_ - 1)];
  solution.newest_covariance = system_.LastBlockCovariance();
  for (int p = 0; p < size_; ++p) solution.null_matches += *NullMatches(oldest_ + p);
  return solution;
}

void SlidingWindowGraph::MarginalizeOldest() {
  const int kept = std::min(options_.max_between_span, size_ - 1);
  const int n = 3 * (kept + 1);
  LocalMatrix h = LocalMatrix::Zero(n, n);
  LocalVector b = LocalVector::Zero(n);
  double c = 0.0;
  // The previous prior (M2) covers the first prior_.size <= B nodes, all inside (o, K).
  if (prior_.size > 0) {
    const LocalVector delta = PriorIncrement(prior_, estimates_.data());
    const int m = 3 * prior_.size;
    c += PriorCost(prior_, delta);
    b.head(m) += prior_.gradient + prior_.information * delta;
    h.topLeftCorner(m, m) += prior_.information;
  }
  const Node& oldest = nodes_[Slot(0)];
  const Se2& x = estimates_[0];
  for (int k = 0; k < oldest.unary_count; ++k) {
    UnaryFactor& factor = Unary(0, k);
    const Eigen::Vector3d error = PriorError(x, factor.measurement);
    const MixtureChoice choice = SelectMixtureComponent(factor.mixture, error);
    factor.component = choice.component;
    c += choice.cost;
    h.topLeftCorner<3, 3>() += choice.information;
    b.head<3>() += choice.information * error;
  }
  for (int k = 0; k < oldest.between_count; ++k) {
    const BetweenFactor& factor = Between(0, k);
    const BetweenLinearization lin =
        LinearizeBetween(x, estimates_[static_cast<std::size_t>(factor.span)], factor.measurement);
    const int t = 3 * factor.span;
    const Eigen::Matrix3d omega_a = factor.information * lin.jacobian_i;
    const Eigen::Matrix3d omega_b = factor.information * lin.jacobian_j;
    c += lin.error.dot(factor.information * lin.error);
    h.topLeftCorner<3, 3>() += lin.jacobian_i.transpose() * omega_a;
    h.block<3, 3>(t, t) += lin.jacobian_j.transpose() * omega_b;
    h.block<3, 3>(t, 0) += lin.jacobian_j.transpose() * omega_a;
    h.block<3, 3>(0, t) += omega_a.transpose() * lin.jacobian_j;
    b.head<3>() += omega_a.transpose() * lin.error;
    b.segment<3>(t) += omega_b.transpose() * lin.error;
  }
  prior_ = EliminateFirstNode(h, b, c, estimates_.data() + 1, kept);  // M1
  DropOldest();
}

void SlidingWindowGraph::DropOldest() {
  // Drop the slot; estimates stay in window order.
  const auto window = static_cast<std::ptrdiff_t>(size_);
  std::copy(estimates_.begin() + 1, estimates_.begin() + window, estimates_.begin());
  head_ = (head_ + 1) % nodes_.size();
  --size_;
  ++oldest_;
}

}  // namespace flat2d::localization::graph
