#include "localization/graph/banded_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace flat2d::localization::graph {
namespace {

// The inverse of the Cholesky factor of a symmetric 3x3 block, in closed form: the
// generic Eigen paths for 3x3 triangular solves cost more than the arithmetic. False when
// `d` is not positive definite.
bool InvertedCholesky(const Eigen::Matrix3d& d, Eigen::Matrix3d& l_inverse) {
  const double p00 = d(0, 0);
  if (!(p00 > 0.0) || !std::isfinite(p00)) return false;
  const double l00 = std::sqrt(p00);
  const double l10 = d(1, 0) / l00;
  const double l20 = d(2, 0) / l00;
  const double p11 = d(1, 1) - l10 * l10;
  if (!(p11 > 0.0) || !std::isfinite(p11)) return false;
  const double l11 = std::sqrt(p11);
  const double l21 = (d(2, 1) - l20 * l10) / l11;
  const double p22 = d(2, 2) - l20 * l20 - l21 * l21;
  if (!(p22 > 0.0) || !std::isfinite(p22)) return false;
  const double l22 = std::sqrt(p22);
  const double m00 = 1.0 / l00;
  const double m11 = 1.0 / l11;
  const double m22 = 1.0 / l22;
  const double m10 = -l10 * m00 * m11;
  l_inverse << m00, 0.0, 0.0,  //
      m10, m11, 0.0,           //
      -(l20 * m00 + l21 * m10) * m22, -l21 * m11 * m22, m22;
  return true;
}

}  // namespace

BlockBandedSystem::BlockBandedSystem(int max_blocks, int bandwidth)
    : max_blocks_(max_blocks),
      bandwidth_(bandwidth),
      h_diagonal_(Index(max_blocks), Eigen::Matrix3d::Zero()),
      h_band_(Index(max_blocks * bandwidth), Eigen::Matrix3d::Zero()),
      gradient_(Index(max_blocks), Eigen::Vector3d::Zero()),
      l_inverse_(Index(max_blocks), Eigen::Matrix3d::Zero()),
      l_band_(Index(max_blocks * bandwidth), Eigen::Matrix3d::Zero()),
      step_(Index(max_blocks), Eigen::Vector3d::Zero()) {
  assert(max_blocks >= 1 && bandwidth >= 1);
}

void BlockBandedSystem::Reset(int blocks) {
  assert(blocks >= 0 && blocks <= max_blocks_);
  size_ = blocks;
  for (int k = 0; k < blocks; ++k) {
    h_diagonal_[Index(k)].setZero();
    gradient_[Index(k)].setZero();
    for (int d = 1; d <= bandwidth_; ++d) h_band_[OffIndex(k, d)].setZero();
  }
}

void BlockBandedSystem::AddDiagonal(int k, const Eigen::Matrix3d& block) {
  assert(k >= 0 && k < size_);
  h_diagonal_[Index(k)] += block;
}

void BlockBandedSystem::AddOffDiagonal(int row, int col, const Eigen::Matrix3d& block) {
  assert(row < size_ && col >= 0 && row - col >= 1 && row - col <= bandwidth_);
  h_band_[OffIndex(row, row - col)] += block;
}

void BlockBandedSystem::AddGradient(int k, const Eigen::Vector3d& gradient) {
  assert(k >= 0 && k < size_);
  gradient_[Index(k)] += gradient;
}

bool BlockBandedSystem::Factorize(double lambda) {
  for (int k = 0; k < size_; ++k) {
    const int first = std::max(0, k - bandwidth_);
    // Off-diagonal blocks of row k, left to right (B1, first line).
    for (int j = first; j < k; ++j) {
      Eigen::Matrix3d s = h_band_[OffIndex(k, k - j)];
      for (int m = first; m < j; ++m) {
        s.noalias() -= l_band_[OffIndex(k, k - m)] * l_band_[OffIndex(j, j - m)].transpose();
      }
      l_band_[OffIndex(k, k - j)].noalias() = s * l_inverse_[Index(j)].transpose();
    }
    // The diagonal block (B1, second line).
    Eigen::Matrix3d d = h_diagonal_[Index(k)];
    if (lambda > 0.0) d.diagonal() += lambda * h_diagonal_[Index(k)].diagonal();
    for (int m = first; m < k; ++m) {
      const Eigen::Matrix3d& l_km = l_band_[OffIndex(k, k - m)];
      d.noalias() -= l_km * l_km.transpose();
    }
    if (!InvertedCholesky(d, l_inverse_[Index(k)])) return false;
  }
  return size_ > 0;
}

void BlockBandedSystem::SolveStep() {
  // Forward: L y = -b.
  for (int k = 0; k < size_; ++k) {
    Eigen::Vector3d r = -gradient_[Index(k)];
    for (int j = std::max(0, k - bandwidth_); j < k; ++j) {
      r.noalias() -= l_band_[OffIndex(k, k - j)] * step_[Index(j)];
    }
    step_[Index(k)].noalias() = l_inverse_[Index(k)] * r;
  }
  // Backward: L^T dx = y.
  for (int k = size_ - 1; k >= 0; --k) {
    Eigen::Vector3d r = step_[Index(k)];
    for (int j = k + 1; j <= std::min(size_ - 1, k + bandwidth_); ++j) {
      r.noalias() -= l_band_[OffIndex(j, j - k)].transpose() * step_[Index(j)];
    }
    step_[Index(k)].noalias() = l_inverse_[Index(k)].transpose() * r;
  }
}

Eigen::Matrix3d BlockBandedSystem::LastBlockCovariance() const {
  assert(size_ > 0);
  const Eigen::Matrix3d& l_inverse = l_inverse_[Index(size_ - 1)];
  const Eigen::Matrix3d covariance = l_inverse.transpose() * l_inverse;  // B3
  return 0.5 * (covariance + covariance.transpose());
}

}  // namespace flat2d::localization::graph
