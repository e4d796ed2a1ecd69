#include "maps/range3d/surface_statistics.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace flat2d::maps::range3d {

namespace {

struct Rectangle {
  int row0, col0, row1, col1;
};

Rectangle NeighbourhoodOf(const Eigen::Vector2f& half_size, const PixelInterval& interval, int row, int col) {
  const int half_cols = static_cast<int>(std::ceil(half_size.x()));
  const int half_rows = static_cast<int>(std::ceil(half_size.y()));
  return {std::max(row - half_rows, static_cast<int>(interval.row_min)),
          std::max(col - half_cols, static_cast<int>(interval.col_min)),
          std::min(row + half_rows, static_cast<int>(interval.row_max)),
          std::min(col + half_cols, static_cast<int>(interval.col_max))};
}

// Eq. 3.35 from the moments: mean and (biased) covariance.
Eigen::Matrix3d CovarianceOf(const PointMoments& m) {
  const double n = m[0];
  const Eigen::Vector3d mean(m[1] / n, m[2] / n, m[3] / n);
  Eigen::Matrix3d second;
  second << m[4], m[5], m[6], m[5], m[7], m[8], m[6], m[8], m[9];
  return second / n - mean * mean.transpose();
}

}  // namespace

void AssignSurface(const Eigen::Matrix3d& covariance, const Eigen::Vector3f& towards_viewpoint,
                   const SurfaceStatisticsOptions& options, std::size_t index, SurfelCloud& cloud) {
  // The moments needed double; the centred covariance does not, and the float solver is
  // twice as fast on the one call per pixel.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> eigen;
  eigen.computeDirect(covariance.cast<float>());  // Eq. 5.1, eigenvalues ascending
  const Eigen::Vector3f lambda = eigen.eigenvalues().cwiseMax(0.0F);
  const float total = lambda.sum();
  if (!(total > 0.0F)) return;
  Eigen::Vector3f normal = eigen.eigenvectors().col(0).normalized();
  if (normal.dot(towards_viewpoint) < 0.0F) normal = -normal;

  const float sigma = lambda[0] / total;
  cloud.normals[index] = normal;
  cloud.curvature[index] = sigma;
  // Omega^s = (Eq. 5.2)^-1 and Omega^n (Eq. 5.14) where flat, the identity elsewhere.
  cloud.disc_gain[index] = sigma < options.flat_curvature ? 1.0F / options.disc_epsilon - 1.0F : 0.0F;
}

void SurfaceStatistics::Compute(const RangeProjection& projection, const IndexImage& image, SurfelCloud& cloud) {
  integral_.Build(image, cloud.points);
  intervals_.Build(image, options_.depth_jump_ratio);
  for (int row = 0; row < image.rows(); ++row) {
    for (int col = 0; col < image.cols(); ++col) {
      if (image.at(row, col) >= 0) ComputePixel(projection, image, row, col, cloud);
    }
  }
}

void SurfaceStatistics::ComputePixel(const RangeProjection& projection, const IndexImage& image, int row, int col,
                                     SurfelCloud& cloud) const {
  const auto index = static_cast<std::size_t>(image.at(row, col));
  const Eigen::Vector2f half_size =
      (options_.radius_m * projection.PixelsPerMetre(image.depth(row, col)))
          .cwiseMin(static_cast<float>(options_.max_half_size_px))
          .cwiseMax(1.0F);
  const Rectangle r = NeighbourhoodOf(half_size, intervals_.at(row, col), row, col);
  const PointMoments moments = integral_.Sum(r.row0, r.col0, r.row1, r.col1);
  if (moments[0] < static_cast<double>(options_.min_points)) return;

  AssignSurface(CovarianceOf(moments), -cloud.points[index], options_, index, cloud);
}

}  // namespace flat2d::maps::range3d
