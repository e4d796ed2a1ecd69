// Index images (thesis 5.1.2): for each pixel of a projection, the index of the point of
// an array that lands there, chosen by a depth buffer.
//
// Points are not copied or reordered: registration walks the pixels and reads the clouds
// through the indices. Where several points fall in one pixel the nearest wins, and with
// normals, only a point whose normal faces the centre of projection competes (a surface
// seen from behind cannot be what the sensor sees).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "maps/range3d/projection.hpp"

namespace flat2d::maps::range3d {

class IndexImage {
 public:
  // The buffers of rows x cols pixels, allocated once; Build() reuses them.
  void Reserve(int rows, int cols);

  // Projects camera_T_points * points[i] for every i (Eq. 5.4, 5.5). `normals` may be
  // empty; otherwise normals[i] is rotated likewise and a zero normal disqualifies.
  void Build(const RangeProjection& projection, const std::vector<Eigen::Vector3f>& points,
             const std::vector<Eigen::Vector3f>& normals, const Eigen::Isometry3f& camera_T_points);

  // Empties every pixel (buffers kept), for filling with Set().
  void Clear(int rows, int cols);
  // Pixel (row, col) shows point `index` at `depth`: for images whose layout is known.
  void Set(int row, int col, std::int32_t index, float depth) {
    index_[Offset(row, col)] = index;
    depth_[Offset(row, col)] = depth;
  }

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  std::int32_t at(int row, int col) const { return index_[Offset(row, col)]; }
  float depth(int row, int col) const { return depth_[Offset(row, col)]; }
  const std::vector<std::int32_t>& indices() const { return index_; }

 private:
  std::size_t Offset(int row, int col) const { return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col); }

  int rows_ = 0;
  int cols_ = 0;
  std::vector<std::int32_t> index_;  // -1 = empty
  std::vector<float> depth_;
};

}  // namespace flat2d::maps::range3d
