#include "maps/range3d/index_image.hpp"

#include <algorithm>
#include <limits>

namespace flat2d::maps::range3d {

void IndexImage::Reserve(int rows, int cols) {
  rows_ = rows;
  cols_ = cols;
  const auto pixels = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  index_.resize(pixels);
  depth_.resize(pixels);
}

void IndexImage::Clear(int rows, int cols) {
  Reserve(rows, cols);
  std::fill(index_.begin(), index_.end(), -1);
  std::fill(depth_.begin(), depth_.end(), std::numeric_limits<float>::infinity());
}

void IndexImage::Build(const RangeProjection& projection, const std::vector<Eigen::Vector3f>& points,
                       const std::vector<Eigen::Vector3f>& normals, const Eigen::Isometry3f& camera_T_points) {
  if (rows_ != projection.rows() || cols_ != projection.cols()) Reserve(projection.rows(), projection.cols());
  std::fill(index_.begin(), index_.end(), -1);
  std::fill(depth_.begin(), depth_.end(), std::numeric_limits<float>::infinity());
  const bool with_normals = !normals.empty();
  const Eigen::Matrix3f rotation = camera_T_points.linear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f p = camera_T_points * points[i];
    if (with_normals) {
      if (normals[i].squaredNorm() < 0.5F) continue;
      if ((rotation * normals[i]).dot(p) > 0.0F) continue;  // faces away from the viewpoint
    }
    const Pixel pixel = projection.Project(p);
    if (!pixel.valid()) continue;
    const std::size_t offset = Offset(pixel.row, pixel.col);
    if (pixel.depth < depth_[offset]) {
      depth_[offset] = pixel.depth;
      index_[offset] = static_cast<std::int32_t>(i);
    }
  }
}

}  // namespace flat2d::maps::range3d
