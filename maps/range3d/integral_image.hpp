// Integral images of point moments (thesis App. D; Holzer et al. 2012): the count, sum
// and sum of outer products of the points in any pixel rectangle in O(1), which gives
// the mean and covariance of Eq. 3.35 without a neighbour search.
//
// Sums are double: a covariance of millimetre spread is a small difference of sums of
// squares over hundreds of thousands of pixels, which float cannot hold.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "maps/range3d/index_image.hpp"

namespace flat2d::maps::range3d {

// count, x, y, z, xx, xy, xz, yy, yz, zz
using PointMoments = std::array<double, 10>;

class IntegralImage {
 public:
  // Sums over `image`'s pixels of points[image.at(row, col)]; buffers reused across calls.
  void Build(const IndexImage& image, const std::vector<Eigen::Vector3f>& points);

  // Moments of the pixels in rows [row0, row1] x cols [col0, col1], inclusive.
  PointMoments Sum(int row0, int col0, int row1, int col1) const;

 private:
  const PointMoments& At(int row, int col) const {  // (row, col) of the padded table
    return table_[static_cast<std::size_t>(row) * stride_ + static_cast<std::size_t>(col)];
  }

  std::size_t stride_ = 0;  // cols + 1: row 0 and col 0 are the zero border
  std::vector<PointMoments> table_;
};

}  // namespace flat2d::maps::range3d
