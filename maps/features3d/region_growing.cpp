#include "maps/features3d/region_growing.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::maps::features3d {

const Clusters& RegionGrowing::Segment(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud) {
  const std::size_t pixels = static_cast<std::size_t>(image.rows()) * static_cast<std::size_t>(image.cols());
  labelled_.assign(pixels, 0);
  pool_.reserve(pixels);
  clusters_.points.clear();
  clusters_.begin.assign(1, 0);
  for (std::size_t offset = 0; offset < pixels; ++offset) {
    const std::int32_t index = image.indices()[offset];
    if (index < 0 || labelled_[offset] != 0 || !cloud.has_normal(static_cast<std::size_t>(index))) continue;
    const auto [size, rows] = Grow(offset, image, cloud);
    if (size > options_.min_cluster_points() && rows >= static_cast<int>(options_.min_rows())) {
      clusters_.begin.push_back(clusters_.points.size());
    } else {
      clusters_.points.resize(clusters_.points.size() - size);  // dropped, its pixels stay labelled
    }
  }
  return clusters_;
}

std::pair<std::size_t, int> RegionGrowing::Grow(std::size_t start, const range3d::IndexImage& image,
                                                const range3d::SurfelCloud& cloud) {
  const int rows = image.rows(), cols = image.cols();
  const int reach = static_cast<int>(options_.neighbour_cols());
  const std::int32_t* indices = image.indices().data();
  pool_.clear();
  pool_.push_back(start);
  labelled_[start] = 1;
  int top = rows, bottom = -1;
  for (std::size_t head = 0; head < pool_.size(); ++head) {  // the pool is a FIFO over pool_
    const std::size_t offset = pool_[head];
    const auto seed = static_cast<std::size_t>(indices[offset]);
    clusters_.points.push_back(static_cast<std::int32_t>(seed));
    const int row = static_cast<int>(offset / static_cast<std::size_t>(cols));
    const int col = static_cast<int>(offset % static_cast<std::size_t>(cols));
    top = std::min(top, row);
    bottom = std::max(bottom, row);
    const Seed s = SeedAt(cloud, seed);
    for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1); ++r) {
      const std::size_t row_start = static_cast<std::size_t>(r) * static_cast<std::size_t>(cols);
      for (int dc = -reach; dc <= reach; ++dc) {
        int c = col + dc;  // the azimuth wraps round
        if (c < 0) c += cols;
        if (c >= cols) c -= cols;
        const std::size_t neighbour = row_start + static_cast<std::size_t>(c);
        const std::int32_t index = indices[neighbour];
        if (index < 0 || labelled_[neighbour] != 0 || !Joins(s, cloud, static_cast<std::size_t>(index))) continue;
        labelled_[neighbour] = 1;
        pool_.push_back(neighbour);
      }
    }
  }
  return {pool_.size(), bottom - top + 1};
}

RegionGrowing::Seed RegionGrowing::SeedAt(const range3d::SurfelCloud& cloud, std::size_t seed) const {
  const Eigen::Vector3f& p = cloud.points[seed];
  const auto max_distance =
      static_cast<float>(options_.max_distance_m() + options_.max_distance_per_m() * static_cast<double>(p.norm()));
  const Eigen::Vector3f direction = cloud.has_line_direction(seed) ? cloud.line_directions[seed] : Eigen::Vector3f::Zero();
  return {p, cloud.normals[seed], direction, max_distance * max_distance};
}

bool RegionGrowing::Joins(const Seed& seed, const range3d::SurfelCloud& cloud, std::size_t candidate) const {
  if (!cloud.has_normal(candidate)) return false;
  const bool near = (seed.point - cloud.points[candidate]).squaredNorm() < seed.max_distance_squared;  // Eq. 8.2
  // Eq. 8.3; between two points of a line (a thin pole) their directions stand for the
  // normals, which may turn about it.
  const bool both_lines = seed.line_direction.squaredNorm() > 0.5F && cloud.has_line_direction(candidate);
  const bool aligned = both_lines ? std::abs(seed.line_direction.dot(cloud.line_directions[candidate])) > min_normal_dot_
                                  : seed.normal.dot(cloud.normals[candidate]) > min_normal_dot_;
  return either_ ? (near || aligned) : (near && aligned);
}

}  // namespace flat2d::maps::features3d
