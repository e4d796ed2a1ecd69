#include "maps/range3d/cross_product_normals.hpp"

#include <algorithm>

namespace flat2d::maps::range3d {

void CrossProductNormals::Compute(const IndexImage& image, SurfelCloud& cloud) {
  intervals_.Build(image, options_.depth_jump_ratio);
  RowSums(image, cloud);
  BlockFilter(image, cloud);
}

// Raw normals of row `row` (Eq. 5.19) into raw_row_; zero where undefined.
void CrossProductNormals::RawNormalRow(const IndexImage& image, const SurfelCloud& cloud, int row) {
  const int rows = image.rows(), cols = image.cols(), d = options_.delta;
  raw_row_.assign(static_cast<std::size_t>(cols), Eigen::Vector3f::Zero());
  if (row < d || row >= rows - d) return;
  for (int col = d; col < cols - d; ++col) {
    const std::int32_t centre = image.at(row, col);
    if (centre < 0) continue;
    const PixelInterval& interval = intervals_.at(row, col);
    if (col - d < interval.col_min || col + d > interval.col_max || row - d < interval.row_min ||
        row + d > interval.row_max) {
      continue;  // a neighbour across a depth jump
    }
    const std::int32_t left = image.at(row, col - d), right = image.at(row, col + d);
    const std::int32_t up = image.at(row - d, col), down = image.at(row + d, col);
    if (left < 0 || right < 0 || up < 0 || down < 0) continue;
    auto point = [&](std::int32_t i) { return cloud.points[static_cast<std::size_t>(i)]; };
    Eigen::Vector3f n = (point(right) - point(left)).cross(point(down) - point(up));  // Eq. 5.19
    const float norm = n.norm();
    if (!(norm > 0.0F)) continue;
    n /= norm;
    if (n.dot(point(centre)) > 0.0F) n = -n;  // towards the viewpoint
    raw_row_[static_cast<std::size_t>(col)] = n;
  }
}

// Row-wise prefix sums of (n, 1) over the raw normals (float holds a row's few hundred unit
// normals exactly enough), each row's taken as its raw normals are made: a block is then
// 2 block + 1 row differences, with less memory than a 2D integral image of doubles, and
// a pixel has a raw normal where its row's count steps up.
void CrossProductNormals::RowSums(const IndexImage& image, const SurfelCloud& cloud) {
  const int rows = image.rows(), cols = image.cols();
  const auto stride = static_cast<std::size_t>(cols) + 1;
  row_sums_.resize(static_cast<std::size_t>(rows) * stride);
  for (int row = 0; row < rows; ++row) {
    RawNormalRow(image, cloud, row);
    Eigen::Vector4f running = Eigen::Vector4f::Zero();
    Eigen::Vector4f* out = &row_sums_[static_cast<std::size_t>(row) * stride];
    out[0] = running;
    for (int col = 0; col < cols; ++col) {
      const Eigen::Vector3f& n = raw_row_[static_cast<std::size_t>(col)];
      if (n.squaredNorm() > 0.5F) running += Eigen::Vector4f(n.x(), n.y(), n.z(), 1.0F);
      out[col + 1] = running;
    }
  }
}

void CrossProductNormals::BlockFilter(const IndexImage& image, SurfelCloud& cloud) {
  const int rows = image.rows(), cols = image.cols(), b = options_.block;
  const auto stride = static_cast<std::size_t>(cols) + 1;
  const float flat_gain = 1.0F / options_.disc_epsilon - 1.0F;
  for (int row = 0; row < rows; ++row) {
    const Eigen::Vector4f* own = &row_sums_[static_cast<std::size_t>(row) * stride];
    for (int col = 0; col < cols; ++col) {
      const std::int32_t index = image.at(row, col);
      if (index < 0 || !(own[col + 1].w() > own[col].w())) continue;  // no raw normal here
      const PixelInterval& interval = intervals_.at(row, col);
      const int r0 = std::max(row - b, static_cast<int>(interval.row_min)), r1 = std::min(row + b, static_cast<int>(interval.row_max));
      const auto c0 = static_cast<std::size_t>(std::max(col - b, static_cast<int>(interval.col_min)));
      const auto c1 = static_cast<std::size_t>(std::min(col + b, static_cast<int>(interval.col_max))) + 1;
      Eigen::Vector4f sum = Eigen::Vector4f::Zero();
      for (int r = r0; r <= r1; ++r) {
        const Eigen::Vector4f* line = &row_sums_[static_cast<std::size_t>(r) * stride];
        sum += line[c1] - line[c0];
      }
      if (sum.w() < static_cast<float>(options_.min_block_normals)) continue;
      const Eigen::Vector3f mean = sum.head<3>() / sum.w();
      const float length = mean.norm();
      const auto i = static_cast<std::size_t>(index);
      cloud.normals[i] = mean / length;
      cloud.curvature[i] = std::max(0.0F, 1.0F - length);
      cloud.disc_gain[i] = cloud.curvature[i] < options_.flat_curvature ? flat_gain : 0.0F;
    }
  }
}

}  // namespace flat2d::maps::range3d
