#include "maps/range3d/point_kdtree.hpp"

#include <nanoflann.hpp>

namespace flat2d::maps::range3d {

namespace {

// Dataset adaptor: member i is points[members[i]], plus alpha * its normal in dims 3..5.
struct PointNormalDataset {
  const std::vector<Eigen::Vector3f>* points = nullptr;
  const std::vector<Eigen::Vector3f>* normals = nullptr;  // null: a 3D tree
  float alpha = 0.0F;
  std::vector<std::uint32_t> members;

  std::size_t kdtree_get_point_count() const { return members.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    const std::uint32_t member = members[i];
    return dim < 3 ? (*points)[member][static_cast<Eigen::Index>(dim)]
                   : alpha * (*normals)[member][static_cast<Eigen::Index>(dim - 3)];
  }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const { return false; }
};

}  // namespace

template <int Dim>
struct PointKdTree<Dim>::Index {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointNormalDataset>,
                                                   PointNormalDataset, Dim, std::uint32_t>;
  PointNormalDataset dataset;
  std::unique_ptr<Tree> tree;
};

template <int Dim>
PointKdTree<Dim>::PointKdTree(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>* normals,
                              float alpha)
    : index_(std::make_unique<Index>()) {
  PointNormalDataset& dataset = index_->dataset;
  dataset.points = &points;
  dataset.normals = normals;
  dataset.alpha = alpha;
  dataset.members.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool usable = points[i].allFinite() && (normals == nullptr || (*normals)[i].squaredNorm() > 0.5F);
    if (usable) dataset.members.push_back(static_cast<std::uint32_t>(i));
  }
  index_->tree = std::make_unique<typename Index::Tree>(Dim, dataset, nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

template <int Dim>
PointKdTree<Dim>::~PointKdTree() = default;

template <int Dim>
std::pair<std::int64_t, float> PointKdTree<Dim>::Nearest(const float* query) const {
  std::uint32_t member = 0;
  float distance_squared = 0.0F;
  if (index_->dataset.members.empty() || index_->tree->knnSearch(query, 1, &member, &distance_squared) == 0) {
    return {-1, 0.0F};
  }
  return {index_->dataset.members[member], distance_squared};
}

template <int Dim>
void PointKdTree<Dim>::WithinRadius(const float* query, float radius,
                                    std::vector<std::pair<std::uint32_t, float>>& found) const {
  found.clear();
  if (index_->dataset.members.empty()) return;
  index_->tree->radiusSearch(query, radius * radius, found, nanoflann::SearchParams(32, 0.0F, false));
  for (auto& [member, distance] : found) member = index_->dataset.members[member];
}

template class PointKdTree<3>;
template class PointKdTree<6>;

}  // namespace flat2d::maps::range3d
