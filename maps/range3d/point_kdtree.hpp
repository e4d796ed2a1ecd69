// nanoflann KD-trees over the clouds of 3D registration: on positions (neighbourhoods for
// the statistics of unorganized clouds) and on (p, alpha n) (thesis Eq. 6.10: nearest
// neighbours that respect the surface orientation, for NICP's KD-tree mode).
//
// The trees index the caller's arrays in place; the arrays must outlive the tree and not
// change while it exists.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace flat2d::maps::range3d {

template <int Dim>
class PointKdTree {
 public:
  // A 3D tree of all points, or (Dim 6) a tree of (p, alpha n) of the points with a normal.
  PointKdTree(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>* normals, float alpha);
  ~PointKdTree();
  PointKdTree(const PointKdTree&) = delete;
  PointKdTree& operator=(const PointKdTree&) = delete;

  // Index (into the caller's arrays) of the nearest member to `query` (Dim floats), and
  // its squared distance; index -1 when the tree is empty.
  std::pair<std::int64_t, float> Nearest(const float* query) const;

  // Members within `radius` of `query`; `found` is reused.
  void WithinRadius(const float* query, float radius, std::vector<std::pair<std::uint32_t, float>>& found) const;

 private:
  struct Index;  // the nanoflann tree and its dataset adaptor
  std::unique_ptr<Index> index_;
};

extern template class PointKdTree<3>;
extern template class PointKdTree<6>;

}  // namespace flat2d::maps::range3d
