#include "maps/range3d/integral_image.hpp"

#include <algorithm>

namespace flat2d::maps::range3d {

namespace {

PointMoments MomentsOf(const Eigen::Vector3f& p) {
  const Eigen::Vector3d q = p.cast<double>();
  const double x = q.x(), y = q.y(), z = q.z();
  return {1.0, x, y, z, x * x, x * y, x * z, y * y, y * z, z * z};
}

}  // namespace

void IntegralImage::Build(const IndexImage& image, const std::vector<Eigen::Vector3f>& points) {
  const auto rows = static_cast<std::size_t>(image.rows());
  const auto cols = static_cast<std::size_t>(image.cols());
  stride_ = cols + 1;
  table_.resize((rows + 1) * stride_);
  std::fill(table_.begin(), table_.begin() + static_cast<std::ptrdiff_t>(stride_), PointMoments{});
  for (std::size_t row = 0; row < rows; ++row) {
    PointMoments running{};
    PointMoments* out = &table_[(row + 1) * stride_];
    const PointMoments* above = &table_[row * stride_];
    out[0] = PointMoments{};
    for (std::size_t col = 0; col < cols; ++col) {
      const std::int32_t index = image.at(static_cast<int>(row), static_cast<int>(col));
      if (index >= 0) {
        const PointMoments m = MomentsOf(points[static_cast<std::size_t>(index)]);
        for (std::size_t k = 0; k < m.size(); ++k) running[k] += m[k];
      }
      for (std::size_t k = 0; k < running.size(); ++k) out[col + 1][k] = above[col + 1][k] + running[k];
    }
  }
}

PointMoments IntegralImage::Sum(int row0, int col0, int row1, int col1) const {
  const PointMoments& a = At(row1 + 1, col1 + 1);
  const PointMoments& b = At(row0, col1 + 1);
  const PointMoments& c = At(row1 + 1, col0);
  const PointMoments& d = At(row0, col0);
  PointMoments sum;
  for (std::size_t k = 0; k < sum.size(); ++k) sum[k] = a[k] - b[k] - c[k] + d[k];
  return sum;
}

}  // namespace flat2d::maps::range3d
