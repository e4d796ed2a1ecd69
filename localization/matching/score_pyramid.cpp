#include "localization/matching/score_pyramid.hpp"

#include <algorithm>
#include <string>

namespace flat2d::localization {

ScorePyramid::ScorePyramid(std::size_t max_cells, int max_levels)
    : max_levels_(std::max(1, max_levels)),
      max_cells_(max_cells),
      levels_(static_cast<std::size_t>(max_levels_ - 1) * max_cells, 0) {}

Status ScorePyramid::Rebuild(const ScoreTable& table) {
  if (table.geometry().CellCount() > max_cells_) {
    return MakeError("score pyramid: map of " + std::to_string(table.geometry().CellCount()) +
                     " cells exceeds the preallocated " + std::to_string(max_cells_));
  }
  table_ = &table;
  width_ = table.width();
  height_ = table.height();
  for (int level = 1; level < max_levels_; ++level) BuildLevel(level);
  return Status::Ok();
}

const std::uint8_t* ScorePyramid::Level(int level) const {
  if (level == 0) return table_->data();
  return levels_.data() + static_cast<std::size_t>(level - 1) * max_cells_;
}

// Level k (x, y) = max of level k-1 at (x, y), (x + h, y), (x, y + h), (x + h, y + h) with
// h = 2^(k-1): the four half-size blocks that tile the 2^k block. Cells past the map's far
// edge score 0 and drop out.
void ScorePyramid::BuildLevel(int level) {
  const std::uint8_t* below = Level(level - 1);
  std::uint8_t* out = levels_.data() + static_cast<std::size_t>(level - 1) * max_cells_;
  const int half = 1 << (level - 1);
  const std::size_t stride = static_cast<std::size_t>(width_);
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* row = below + static_cast<std::size_t>(y) * stride;
    const std::uint8_t* upper = y + half < height_ ? row + static_cast<std::size_t>(half) * stride
                                                   : nullptr;
    std::uint8_t* out_row = out + static_cast<std::size_t>(y) * stride;
    for (int x = 0; x < width_; ++x) {
      const bool right = x + half < width_;
      std::uint8_t m = row[x];
      if (right) m = std::max(m, row[x + half]);
      if (upper != nullptr) {
        m = std::max(m, upper[x]);
        if (right) m = std::max(m, upper[x + half]);
      }
      out_row[x] = m;
    }
  }
}

}  // namespace flat2d::localization
