#include "maps/range3d/surface_statistics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>

namespace flat2d::maps::range3d {

namespace {

struct Rectangle {
  int row0, col0, row1, col1;
};

// ceil of a positive float without the libm call SSE2 needs for std::ceil.
int CeilOfPositive(float value) {
  const auto truncated = static_cast<int>(value);
  return static_cast<float>(truncated) < value ? truncated + 1 : truncated;
}

Rectangle NeighbourhoodOf(const Eigen::Vector2f& half_size, const PixelInterval& interval, int row, int col) {
  const int half_cols = CeilOfPositive(half_size.x());
  const int half_rows = CeilOfPositive(half_size.y());
  return {std::max(row - half_rows, static_cast<int>(interval.row_min)),
          std::max(col - half_cols, static_cast<int>(interval.col_min)),
          std::min(row + half_rows, static_cast<int>(interval.row_max)),
          std::min(col + half_cols, static_cast<int>(interval.col_max))};
}

// Eq. 3.35 from the moments: mean and (biased) covariance.
Eigen::Matrix3d CovarianceOf(const PointMoments& m) {
  const double inverse_n = 1.0 / m[0];
  const Eigen::Vector3d mean(m[1] * inverse_n, m[2] * inverse_n, m[3] * inverse_n);
  Eigen::Matrix3d second;
  second << m[4], m[5], m[6], m[5], m[7], m[8], m[6], m[8], m[9];
  return second * inverse_n - mean * mean.transpose();
}

// Sum of the principal 2x2 minors: the coefficient of l in det(C - l I), and the sum of the
// eigenvalues' pairwise products.
double SecondMinors(const Eigen::Matrix3d& c) {
  return c(0, 0) * c(1, 1) - c(0, 1) * c(0, 1) + c(0, 0) * c(2, 2) - c(0, 2) * c(0, 2) + c(1, 1) * c(2, 2) -
         c(1, 2) * c(1, 2);
}

// For C - l I of rank two (l a simple eigenvalue): the largest cross product of two of its
// rows, which is along l's eigenvector; not normalized.
Eigen::Vector3d LargestRowCross(const Eigen::Matrix3d& shifted) {
  const Eigen::Vector3d r0 = shifted.row(0), r1 = shifted.row(1), r2 = shifted.row(2);
  const std::array<Eigen::Vector3d, 3> candidates{r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  std::size_t best = 0;
  for (std::size_t k = 1; k < 3; ++k) {
    if (candidates[k].squaredNorm() > candidates[best].squaredNorm()) best = k;
  }
  return candidates[best];
}

// The smallest eigenvalue and its unit eigenvector of a covariance (Eq. 5.1), without the
// trigonometric closed form of all three. det(C - l I) is convex and decreasing left of the
// smallest root l0, so from l = 0 <= l0 root-finding climbs to l0; Halley's steps (cubic
// convergence) take 3 on most pixels of a TUM frame where Newton's take 4-5. The
// eigenvector is the largest cross product of two rows of C - l0 I. Empty where that is
// ill-posed (l0 < 0 from rounding, a repeated l0, no convergence): the caller falls back
// to the general closed form there. Both in double: a float solver cannot resolve an l0
// below ~1e-7 of the trace (a 1 mm thick wall seen over 30 cm, a LiDAR ring's line).
struct SmallestEigen {
  double value;
  Eigen::Vector3d vector;
};

// The root-finding for l0 of one covariance, a step at a time so that a batch of pixels
// can be stepped side by side (each step is a chain of dependent operations ending in a
// division; independent pixels fill the pipeline between them).
class SmallestRoot {
 public:
  SmallestRoot() = default;  // nothing to find
  explicit SmallestRoot(const Eigen::Matrix3d& c)
      : trace_(c.trace()),
        minors_(SecondMinors(c)),
        det_(c.determinant()),
        failed_(!(trace_ > 0.0) || !(det_ >= 0.0)) {}

  static constexpr int kMaxSteps = 24;  // a TUM frame needs 11 at most
  bool active() const { return !converged_ && !failed_; }
  bool converged() const { return converged_; }
  double value() const { return l_; }

  // det(C - l I) = -l^3 + trace l^2 - minors l + det; slope -3 l^2 + 2 trace l - minors.
  void Step() {
    const double value = ((trace_ - l_) * l_ - minors_) * l_ + det_;
    const double slope = (2.0 * trace_ - 3.0 * l_) * l_ - minors_;
    const double bend = 2.0 * trace_ - 6.0 * l_;
    const double denominator = 2.0 * slope * slope - value * bend;
    if (!(slope < 0.0) || !(denominator > 0.0)) {
      failed_ = true;
      return;
    }
    const double delta = -2.0 * value * slope / denominator;  // Halley's step
    l_ += delta;
    converged_ = std::abs(delta) <= 1e-9 * trace_;
  }

 private:
  double trace_ = 0.0, minors_ = 0.0, det_ = 0.0;
  bool failed_ = true;
  double l_ = 0.0;
  bool converged_ = false;
};

std::optional<SmallestEigen> VectorOf(const Eigen::Matrix3d& c, const SmallestRoot& root) {
  if (!root.converged()) return std::nullopt;
  const double l = root.value(), trace = c.trace();
  const Eigen::Vector3d cross = LargestRowCross(c - l * Eigen::Matrix3d::Identity());
  const double norm_squared = cross.squaredNorm();
  // A repeated l0 leaves C - l0 I of rank one: no unique direction from cross products.
  if (!(norm_squared > 1e-12 * trace * trace * trace * trace)) return std::nullopt;
  return SmallestEigen{l, cross * (1.0 / std::sqrt(norm_squared))};
}

// The largest eigenvector of a covariance whose middle eigenvalue is below `max_middle_share`
// of the trace (points along a line), else zero. From l0: the other two eigenvalues are the
// roots of l^2 - s l + p with s = trace - l0, p = minors - l0 s; the vector the largest cross
// product of two rows of C - l_max I, as for l0.
Eigen::Vector3f LineDirection(const Eigen::Matrix3d& c, const std::optional<SmallestEigen>& smallest,
                              float max_middle_share) {
  const double trace = c.trace();
  double l0 = 0.0;
  if (smallest) {
    l0 = smallest->value;
  } else {
    l0 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>().computeDirect(c, Eigen::EigenvaluesOnly).eigenvalues()[0];
  }
  const double s = trace - l0, p = SecondMinors(c) - l0 * s;
  const double root = std::sqrt(std::max(s * s - 4.0 * p, 0.0));
  const double middle = 0.5 * (s - root), largest = 0.5 * (s + root);
  if (!(trace > 0.0) || !(middle < static_cast<double>(max_middle_share) * trace)) return Eigen::Vector3f::Zero();
  const Eigen::Vector3d cross = LargestRowCross(c - largest * Eigen::Matrix3d::Identity());
  const double norm_squared = cross.squaredNorm();
  if (!(norm_squared > 0.0)) return Eigen::Vector3f::Zero();
  return (cross * (1.0 / std::sqrt(norm_squared))).cast<float>();
}

// Normal, curvature and information of point `index` from its covariance and, where found,
// its smallest eigenpair; elsewhere Eigen's closed form.
void Assign(const Eigen::Matrix3d& covariance, const std::optional<SmallestEigen>& smallest,
            const Eigen::Vector3f& towards_viewpoint, const SurfaceStatisticsOptions& options, std::size_t index,
            SurfelCloud& cloud) {
  Eigen::Vector3f normal;
  float sigma = 0.0F;
  if (smallest) {
    normal = smallest->vector.cast<float>();
    sigma = static_cast<float>(smallest->value / covariance.trace());  // l0 >= 0: the sum is the trace
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(covariance);  // Eq. 5.1, eigenvalues ascending
    const Eigen::Vector3d lambda = eigen.eigenvalues().cwiseMax(0.0);
    const double total = lambda.sum();
    if (!(total > 0.0)) return;
    normal = eigen.eigenvectors().col(0).normalized().cast<float>();
    sigma = static_cast<float>(lambda[0] / total);
  }
  if (normal.dot(towards_viewpoint) < 0.0F) normal = -normal;
  if (options.line_max_middle_share > 0.0F && index < cloud.line_directions.size()) {
    cloud.line_directions[index] = LineDirection(covariance, smallest, options.line_max_middle_share);
  }
  cloud.normals[index] = normal;
  cloud.curvature[index] = sigma;
  // Omega^s = (Eq. 5.2)^-1 and Omega^n (Eq. 5.14) where flat, the identity elsewhere.
  cloud.disc_gain[index] = sigma < options.flat_curvature ? 1.0F / options.disc_epsilon - 1.0F : 0.0F;
}

}  // namespace

void AssignSurface(const Eigen::Matrix3d& covariance, const Eigen::Vector3f& towards_viewpoint,
                   const SurfaceStatisticsOptions& options, std::size_t index, SurfelCloud& cloud) {
  SmallestRoot root(covariance);
  for (int step = 0; step < SmallestRoot::kMaxSteps && root.active(); ++step) root.Step();
  Assign(covariance, VectorOf(covariance, root), towards_viewpoint, options, index, cloud);
}

void SurfaceStatistics::Compute(const RangeProjection& projection, const IndexImage& image, SurfelCloud& cloud) {
  if (options_.line_max_middle_share > 0.0F) cloud.line_directions.assign(cloud.size(), Eigen::Vector3f::Zero());
  integral_.Build(image, cloud.points);
  intervals_.Build(image, options_.depth_jump_ratio);
  batch_.clear();
  batch_.reserve(kBatch);
  for (int row = 0; row < image.rows(); ++row) {
    for (int col = 0; col < image.cols(); ++col) {
      if (image.at(row, col) < 0) continue;
      if (const auto covariance = CovarianceAt(projection, image, row, col)) {
        batch_.push_back({static_cast<std::size_t>(image.at(row, col)), *covariance});
      }
      if (batch_.size() == kBatch) AssignBatch(cloud);
    }
  }
  AssignBatch(cloud);
}

std::optional<Eigen::Matrix3d> SurfaceStatistics::CovarianceAt(const RangeProjection& projection,
                                                               const IndexImage& image, int row, int col) const {
  const Eigen::Vector2f half_size =
      (options_.radius_m * projection.PixelsPerMetre(image.depth(row, col)))
          .cwiseMin(static_cast<float>(options_.max_half_size_px))
          .cwiseMax(1.0F);
  const Rectangle r = NeighbourhoodOf(half_size, intervals_.at(row, col), row, col);
  const PointMoments moments = integral_.Sum(r.row0, r.col0, r.row1, r.col1);
  if (moments[0] < static_cast<double>(options_.min_points)) return std::nullopt;
  return CovarianceOf(moments);
}

void SurfaceStatistics::AssignBatch(SurfelCloud& cloud) {
  std::array<SmallestRoot, kBatch> roots{};
  for (std::size_t k = 0; k < batch_.size(); ++k) roots[k] = SmallestRoot(batch_[k].covariance);
  bool any = true;
  for (int step = 0; step < SmallestRoot::kMaxSteps && any; ++step) {
    any = false;
    for (std::size_t k = 0; k < batch_.size(); ++k) {
      if (!roots[k].active()) continue;
      roots[k].Step();
      any = true;
    }
  }
  for (std::size_t k = 0; k < batch_.size(); ++k) {
    const PixelCovariance& pixel = batch_[k];
    Assign(pixel.covariance, VectorOf(pixel.covariance, roots[k]), -cloud.points[pixel.index], options_, pixel.index,
           cloud);
  }
  batch_.clear();
}

}  // namespace flat2d::maps::range3d
