#include "maps/features3d/vertical_removal.hpp"

#include <limits>

namespace flat2d::maps::features3d {

std::size_t VerticalRemoval::Apply(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& up,
                                   range3d::IndexImage& image) {
  column_.reserve(static_cast<std::size_t>(image.rows()));
  vertical_.reserve(static_cast<std::size_t>(image.rows()));
  stack_.reserve(static_cast<std::size_t>(image.rows()));
  std::size_t kept = 0;
  for (int col = 0; col < image.cols(); ++col) {
    column_.clear();
    for (int row = 0; row < image.rows(); ++row) {
      const std::int32_t index = image.at(row, col);
      if (index < 0) continue;
      const Eigen::Vector3f& p = points[static_cast<std::size_t>(index)];
      column_.push_back({row, p - p.dot(up) * up});  // p's projection on the ground plane
    }
    kept += ApplyToColumn(col, image);
  }
  return kept;
}

std::size_t VerticalRemoval::ApplyToColumn(int col, range3d::IndexImage& image) {
  const auto radius_squared = static_cast<float>(options_.ground_radius_m() * options_.ground_radius_m());
  vertical_.assign(column_.size(), 0);
  std::size_t kept = 0;
  for (std::size_t v = 0; v < column_.size(); ++v) {
    if (vertical_[v] != 0) {
      ++kept;
      continue;
    }
    stack_.clear();
    for (std::size_t w = v + 1; w < column_.size(); ++w) {
      if ((column_[v].ground - column_[w].ground).squaredNorm() < radius_squared) stack_.push_back(w);
    }
    if (stack_.size() > options_.min_points_above()) {
      vertical_[v] = 1;
      for (const std::size_t w : stack_) vertical_[w] = 1;
      ++kept;
    } else {
      image.Set(column_[v].row, col, -1, std::numeric_limits<float>::infinity());
    }
  }
  return kept;
}

}  // namespace flat2d::maps::features3d
