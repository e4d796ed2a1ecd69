// Local surface statistics of an organized cloud (thesis 5.1.1): for each point seen in
// the index image, the mean and covariance (Eq. 3.35) of the points within radius R, its
// normal, curvature and the information matrices NICP uses.
//
// Steps: integral images of the point moments (App. D); per pixel a rectangle sized from
// R and the depth (R * pixels-per-metre), shrunk to the pixel's interval (8.1.3) so that it
// does not straddle a depth jump; mean and covariance from four table reads; the
// eigen-decomposition (Eq. 5.1) gives the normal (smallest eigenvector, turned towards the
// viewpoint) and sigma = l1 / (l1 + l2 + l3). Where sigma is below the flatness cut the
// covariance is forced to a disc (Eq. 5.2, eps) and Omega^s, Omega^n are its inverse
// (Eq. 5.13, 5.14), R diag(1/eps, 1, 1) R^T = I + (1/eps - 1) n n^T;
// elsewhere both are the identity.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "maps/range3d/index_image.hpp"
#include "maps/range3d/integral_image.hpp"
#include "maps/range3d/interval_image.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

struct SurfaceStatisticsOptions {
  float radius_m = 0.1F;          // R: 0.1 m indoors (5.1.1)
  int min_points = 8;             // fewer points in the rectangle: normal undefined
  int max_half_size_px = 32;      // bounds the rectangle of near points (work and smoothing)
  float depth_jump_ratio = 0.1F;  // interval cut: neighbours 10 % apart in depth are a jump
  float flat_curvature = 0.02F;   // sigma below this: a disc (the thesis leaves it open)
  float disc_epsilon = 1e-3F;     // eps of Eq. 5.2
  // > 0: where the middle eigenvalue is below this share of the trace the neighbourhood is
  // a line, and its direction (the largest eigenvector) goes into cloud.line_directions.
  // 0: none computed (NICP).
  float line_max_middle_share = 0.0F;
};

class SurfaceStatistics {
 public:
  explicit SurfaceStatistics(const SurfaceStatisticsOptions& options) : options_(options) {}

  // Fills cloud's normals, curvature and information for the points `image` indexes;
  // cloud.points must be what `image` was built from. Points the image does not show
  // keep an undefined normal.
  void Compute(const RangeProjection& projection, const IndexImage& image, SurfelCloud& cloud);

 private:
  // Pixels' covariances are gathered kBatch at a time and their eigenproblems solved side
  // by side (surface_statistics.cpp).
  static constexpr std::size_t kBatch = 32;
  struct PixelCovariance {
    std::size_t index;  // the point's
    Eigen::Matrix3d covariance;
  };

  // Eq. 3.35 over pixel (row, col)'s rectangle; empty with fewer than min_points.
  std::optional<Eigen::Matrix3d> CovarianceAt(const RangeProjection& projection, const IndexImage& image, int row,
                                              int col) const;
  void AssignBatch(SurfelCloud& cloud);

  const SurfaceStatisticsOptions options_;
  IntegralImage integral_;
  IntervalImage intervals_;
  std::vector<PixelCovariance> batch_;  // at most kBatch
};

// Point `index`'s surface from the covariance of its neighbourhood: normal (turned to
// have a positive dot with `towards_viewpoint`), curvature and information. Leaves the
// normal undefined for a degenerate covariance.
void AssignSurface(const Eigen::Matrix3d& covariance, const Eigen::Vector3f& towards_viewpoint,
                   const SurfaceStatisticsOptions& options, std::size_t index, SurfelCloud& cloud);

}  // namespace flat2d::maps::range3d
