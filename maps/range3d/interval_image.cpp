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

void IntervalImage::ScanCols(const IndexImage& image, float jump_ratio) {
  for (int col = 0; col < image.cols(); ++col) {
    ScanLine(
        image.rows(), jump_ratio, [&](int row) { return image.depth(row, col); },
        [&](int row, int bound, bool first) {
          PixelInterval& interval = intervals_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col)];
          (first ? interval.row_min : interval.row_max) = static_cast<std::int16_t>(bound);
        });
  }
}

}  // namespace flat2d::maps::range3d
