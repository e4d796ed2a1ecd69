#include "maps/range3d/interval_image.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::maps::range3d {

namespace {

bool Continuous(float a, float b, float jump_ratio) { return std::abs(a - b) <= jump_ratio * std::min(a, b); }

// Walks `count` pixels of one line (get(i) = depth or +inf when empty) forwards and
// backwards; start[i] / end[i] = the first / last pixel of i's continuous run.
template <typename DepthAt, typename Store>
void ScanLine(int count, float jump_ratio, DepthAt depth_at, Store store) {
  int run_start = 0;
  float previous = -1.0F;
  for (int i = 0; i < count; ++i) {
    const float d = depth_at(i);
    if (!std::isfinite(d)) continue;
    if (previous > 0.0F && !Continuous(previous, d, jump_ratio)) run_start = i;
    store(i, run_start, true);
    previous = d;
  }
  int run_end = count - 1;
  previous = -1.0F;
  for (int i = count - 1; i >= 0; --i) {
    const float d = depth_at(i);
    if (!std::isfinite(d)) continue;
    if (previous > 0.0F && !Continuous(previous, d, jump_ratio)) run_end = i;
    store(i, run_end, false);
    previous = d;
  }
}

}  // namespace

void IntervalImage::Build(const IndexImage& image, float jump_ratio) {
  cols_ = image.cols();
  intervals_.resize(static_cast<std::size_t>(image.rows()) * static_cast<std::size_t>(image.cols()));
  ScanRows(image, jump_ratio);
  ScanCols(image, jump_ratio);
}

void IntervalImage::ScanRows(const IndexImage& image, float jump_ratio) {
  for (int row = 0; row < image.rows(); ++row) {
    ScanLine(
        image.cols(), jump_ratio, [&](int col) { return image.depth(row, col); },
        [&](int col, int bound, bool first) {
          PixelInterval& interval = intervals_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col)];
          (first ? interval.col_min : interval.col_max) = static_cast<std::int16_t>(bound);
        });
  }
}

// All columns at once, row by row: the same walk as ScanLine per column, with each
// column's run state in a row of its own, so that the image is read in memory order.
void IntervalImage::ScanCols(const IndexImage& image, float jump_ratio) {
  const auto cols = static_cast<std::size_t>(image.cols());
  run_bound_.assign(cols, 0);
  previous_.assign(cols, -1.0F);
  auto scan_row = [&](int row, bool first) {
    PixelInterval* line = &intervals_[static_cast<std::size_t>(row) * cols];
    for (std::size_t col = 0; col < cols; ++col) {
      const float d = image.depth(row, static_cast<int>(col));
      if (!std::isfinite(d)) continue;
      if (previous_[col] > 0.0F && !Continuous(previous_[col], d, jump_ratio)) run_bound_[col] = row;
      (first ? line[col].row_min : line[col].row_max) = static_cast<std::int16_t>(run_bound_[col]);
      previous_[col] = d;
    }
  };
  for (int row = 0; row < image.rows(); ++row) scan_row(row, true);
  run_bound_.assign(cols, image.rows() - 1);
  previous_.assign(cols, -1.0F);
  for (int row = image.rows() - 1; row >= 0; --row) scan_row(row, false);
}

}  // namespace flat2d::maps::range3d
