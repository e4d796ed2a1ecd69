#include "localization/graph/marginal_prior.hpp"

#include <Eigen/Eigenvalues>
#include <cassert>

namespace flat2d::localization::graph {
namespace {

// Eigenvalues below this fraction of the largest carry no information (a node without
// factors); the pseudo-inverse drops them instead of amplifying rounding noise.
constexpr double kRelativeRankTolerance = 1e-12;

Eigen::Matrix3d PseudoInverse(const Eigen::Matrix3d& h) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(h);
  const Eigen::Vector3d values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (largest > 0.0 && values(i) > kRelativeRankTolerance * largest) inverse(i) = 1.0 / values(i);
  }
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace

LocalVector PriorIncrement(const MarginalPrior& prior, const Se2* estimates) {
  LocalVector delta(3 * prior.size);
  for (int k = 0; k < prior.size; ++k) {
    delta.segment<3>(3 * k) =
        ComponentDifference(estimates[k], prior.linearization[static_cast<std::size_t>(k)]);
  }
  return delta;
}

double PriorCost(const MarginalPrior& prior, const LocalVector& delta) {
  if (prior.size == 0) return 0.0;
  return prior.constant + 2.0 * prior.gradient.dot(delta) + delta.dot(prior.information * delta);
}

MarginalPrior EliminateFirstNode(const LocalMatrix& h, const LocalVector& b, double c,
                                 const Se2* kept_estimates, int kept) {
  assert(kept >= 0 && kept <= kMaxBetweenSpan && h.rows() == 3 * (kept + 1));
  const int n = 3 * kept;
  const Eigen::Matrix3d h_oo_inverse = PseudoInverse(h.topLeftCorner<3, 3>());
  const auto h_ko = h.bottomLeftCorner(n, 3);
  MarginalPrior prior;
  prior.size = kept;
  for (int k = 0; k < kept; ++k) prior.linearization[static_cast<std::size_t>(k)] = kept_estimates[k];
  // M1.
  const LocalMatrix reduced = h.bottomRightCorner(n, n) - h_ko * h_oo_inverse * h_ko.transpose();
  prior.information = 0.5 * (reduced + reduced.transpose());
  prior.gradient = b.tail(n) - h_ko * (h_oo_inverse * b.head<3>());
  prior.constant = c - b.head<3>().dot(h_oo_inverse * b.head<3>());
  return prior;
}

}  // namespace flat2d::localization::graph
