// Interval images (thesis 8.1.3): for each pixel, how far its neighbourhood rectangle may
// reach left, right, up and down before it crosses a depth discontinuity.
//
// The thesis grows each pixel's interval step by step; here one pass per direction
// records where the current run of continuous depth began, so a whole image costs O(1)
// per pixel whatever the radius. Two neighbours (empty pixels skipped) are continuous
// when their depths differ by at most `jump_ratio` of the nearer one.
#pragma once

#include <cstdint>
#include <vector>

#include "maps/range3d/index_image.hpp"

namespace flat2d::maps::range3d {

struct PixelInterval {
  std::int16_t col_min = 0;
  std::int16_t col_max = 0;
  std::int16_t row_min = 0;
  std::int16_t row_max = 0;
};

class IntervalImage {
 public:
  void Build(const IndexImage& image, float jump_ratio);
  const PixelInterval& at(int row, int col) const {
    return intervals_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col)];
  }

 private:
  void ScanRows(const IndexImage& image, float jump_ratio);
  void ScanCols(const IndexImage& image, float jump_ratio);

  int cols_ = 0;
  std::vector<PixelInterval> intervals_;
  std::vector<int> run_bound_;     // ScanCols: per column, where the current run began (ended)
  std::vector<float> previous_;    // ScanCols: per column, the last depth seen
};

}  // namespace flat2d::maps::range3d
