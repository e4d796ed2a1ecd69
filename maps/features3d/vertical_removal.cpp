#include "maps/features3d/vertical_removal.hpp"

#include <limits>

namespace flat2d::maps::features3d {

std::size_t VerticalRemoval::Apply(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& up,
                                   range3d::IndexImage& image) {
  const auto rows = static_cast<std::size_t>(image.rows());
  for (auto* v : {&ground_x_, &ground_y_}) v->reserve(rows);
  rows_.reserve(rows);
  vertical_.reserve(rows);
  // p - (p . up) up = (p . axis_x) axis_x + (p . axis_y) axis_y: distances on the ground
  // plane are those of the 2D coordinates.
  const Eigen::Vector3f axis_x = up.unitOrthogonal();
  const Eigen::Vector3f axis_y = up.cross(axis_x);
  std::size_t kept = 0;
  for (int col = 0; col < image.cols(); ++col) {
    rows_.clear();
    ground_x_.clear();
    ground_y_.clear();
    for (int row = 0; row < image.rows(); ++row) {
      const std::int32_t index = image.at(row, col);
      if (index < 0) continue;
      const Eigen::Vector3f& p = points[static_cast<std::size_t>(index)];
      rows_.push_back(row);
      ground_x_.push_back(p.dot(axis_x));
      ground_y_.push_back(p.dot(axis_y));
    }
    kept += ApplyToColumn(col, image);
  }
  return kept;
}

std::size_t VerticalRemoval::CountBelow(std::size_t v, float radius_squared) const {
  const float x = ground_x_[v], y = ground_y_[v];
  std::size_t count = 0;
  for (std::size_t w = v + 1; w < rows_.size(); ++w) {
    const float dx = ground_x_[w] - x, dy = ground_y_[w] - y;
    count += dx * dx + dy * dy < radius_squared ? 1U : 0U;
  }
  return count;
}

std::size_t VerticalRemoval::ApplyToColumn(int col, range3d::IndexImage& image) {
  const auto radius_squared = static_cast<float>(options_.ground_radius_m() * options_.ground_radius_m());
  vertical_.assign(rows_.size(), 0);
  std::size_t kept = 0;
  for (std::size_t v = 0; v < rows_.size(); ++v) {
    if (vertical_[v] != 0) {
      ++kept;
      continue;
    }
    if (CountBelow(v, radius_squared) <= options_.min_points_above()) {
      image.Set(rows_[v], col, -1, std::numeric_limits<float>::infinity());
      continue;
    }
    ++kept;  // v and its stack are vertical
    const float x = ground_x_[v], y = ground_y_[v];
    for (std::size_t w = v + 1; w < rows_.size(); ++w) {
      const float dx = ground_x_[w] - x, dy = ground_y_[w] - y;
      vertical_[w] |= dx * dx + dy * dy < radius_squared ? 1U : 0U;
    }
  }
  return kept;
}

}  // namespace flat2d::maps::features3d
