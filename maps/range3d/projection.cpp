#include "maps/range3d/projection.hpp"

#include <algorithm>
#include <array>
#include <cassert>

namespace flat2d::maps::range3d {

namespace {

// Elevation bins of ~0.01 deg: finer than any LiDAR's laser spacing (0.33 deg at least).
constexpr float kLutBinRad = 0.0002F;

}  // namespace

RangeProjection RangeProjection::Pinhole(const PinholeIntrinsics& intrinsics) {
  RangeProjection projection;
  projection.pinhole_ = true;
  projection.intrinsics_ = intrinsics;
  projection.rows_ = intrinsics.rows;
  projection.cols_ = intrinsics.cols;
  return projection;
}

RangeProjection RangeProjection::Spherical(const SphericalLayout& layout) {
  RangeProjection projection;
  projection.pinhole_ = false;
  const std::vector<float>& elevation = layout.row_elevation_rad;
  const bool descending = std::is_sorted(elevation.rbegin(), elevation.rend()) &&
                          std::adjacent_find(elevation.begin(), elevation.end()) == elevation.end();
  const bool shifts_fit = layout.row_column_shift.empty() || layout.row_column_shift.size() == elevation.size();
  if (elevation.size() < 2 || layout.cols <= 0 || !descending || !shifts_fit) return projection;

  projection.rows_ = static_cast<int>(elevation.size());
  projection.cols_ = layout.cols;
  projection.row_elevation_ = elevation;
  projection.row_column_shift_ = layout.row_column_shift;
  projection.row_column_shift_.resize(elevation.size(), 0.0F);
  projection.cols_per_rad_ = static_cast<float>(layout.cols) / (2.0F * kPi);
  projection.mean_row_spacing_rad_ = (elevation.front() - elevation.back()) / static_cast<float>(elevation.size() - 1);

  // A point belongs to the row whose elevation is nearest, up to half the gap to the next
  // row; beyond the outermost rows, up to half the outermost gap.
  const std::size_t last = elevation.size() - 1;
  const float top = elevation[0] + 0.5F * (elevation[0] - elevation[1]);
  const float bottom = elevation[last] - 0.5F * (elevation[last - 1] - elevation[last]);
  projection.lut_min_elevation_ = bottom;
  projection.lut_bins_per_rad_ = 1.0F / kLutBinRad;
  const auto bins = static_cast<std::size_t>(std::ceil((top - bottom) / kLutBinRad));
  projection.elevation_lut_.assign(bins, -1);
  std::size_t row = last;
  for (std::size_t bin = 0; bin < bins; ++bin) {
    const float e = bottom + (static_cast<float>(bin) + 0.5F) * kLutBinRad;
    while (row > 0 && std::abs(elevation[row - 1] - e) < std::abs(elevation[row] - e)) --row;
    projection.elevation_lut_[bin] = static_cast<std::int16_t>(row);
  }
  return projection;
}

RangeProjection RangeProjection::SphericalBinned(int cols, int rows, float min_elevation_rad,
                                                 float max_elevation_rad) {
  SphericalLayout layout;
  layout.cols = cols;
  const float step = (max_elevation_rad - min_elevation_rad) / static_cast<float>(std::max(rows, 1));
  for (int row = 0; row < rows; ++row) {
    layout.row_elevation_rad.push_back(max_elevation_rad - (static_cast<float>(row) + 0.5F) * step);
  }
  return Spherical(layout);
}

RangeProjection RangeProjection::ColumnsDividedBy(int scale) const {
  if (pinhole_ || rows_ == 0 || scale < 1 || cols_ % scale != 0) return Spherical({});
  SphericalLayout layout{cols_ / scale, row_elevation_, row_column_shift_};
  for (float& shift : layout.row_column_shift) shift /= static_cast<float>(scale);
  return Spherical(layout);
}

void RangeProjection::ProjectSpherical(const float* x, const float* y, const float* z, std::size_t count,
                                       std::int32_t* offset, float* depth) const {
  // First pass: the fine elevation bin (in `offset`) and the unshifted column, as
  // ProjectSpherical(p) computes them. The bin is the floor of a value >= 0 where valid, so
  // truncation is the floor there; a bin below 0 is marked -1.
  assert(count <= kMaxBatch);
  std::array<float, kMaxBatch> column;
  // Members copied to locals: the stores below could otherwise alias them for the compiler.
  const auto bins = static_cast<float>(elevation_lut_.size());
  const float min_elevation = lut_min_elevation_, bins_per_rad = lut_bins_per_rad_, cols_per_rad = cols_per_rad_;
  for (std::size_t i = 0; i < count; ++i) {
    const float range_xy_squared = x[i] * x[i] + y[i] * y[i];
    const float range = std::sqrt(range_xy_squared + z[i] * z[i]);
    const float elevation = FastAtan2(z[i], std::sqrt(range_xy_squared));
    const float bin = (elevation - min_elevation) * bins_per_rad;
    const bool valid = (range > 0.0F) & (bin >= 0.0F) & (bin < bins);
    // Selects before the conversions: a float outside int's range (a NaN point) must not
    // be converted.
    const float col = (FastAtan2(y[i], x[i]) + kPi) * cols_per_rad;
    offset[i] = static_cast<std::int32_t>(valid ? bin : -1.0F);
    depth[i] = range;
    column[i] = valid ? col : 0.0F;
  }
  // Second pass: the row, then the row's column shift.
  for (std::size_t i = 0; i < count; ++i) {
    if (offset[i] < 0) continue;
    const int row = elevation_lut_[static_cast<std::size_t>(offset[i])];
    if (row < 0) {
      offset[i] = -1;
      continue;
    }
    const float shifted = column[i] + row_column_shift_[static_cast<std::size_t>(row)];
    offset[i] = row * cols_ + WrappedColumn(static_cast<int>(std::floor(shifted)));
  }
}

Eigen::Vector3f RangeProjection::Unproject(int row, int col, float depth) const {
  if (pinhole_) {  // Eq. 3.11
    return {(static_cast<float>(col) - intrinsics_.cx) * depth / intrinsics_.fx,
            (static_cast<float>(row) - intrinsics_.cy) * depth / intrinsics_.fy, depth};
  }
  const float azimuth =
      (static_cast<float>(col) + 0.5F - row_column_shift_[static_cast<std::size_t>(row)]) / cols_per_rad_ - kPi;
  const float elevation = row_elevation_[static_cast<std::size_t>(row)];
  const float horizontal = depth * std::cos(elevation);
  return {horizontal * std::cos(azimuth), horizontal * std::sin(azimuth), depth * std::sin(elevation)};
}

Eigen::Vector2f RangeProjection::PixelsPerMetre(float depth) const {
  if (!(depth > 0.0F)) return Eigen::Vector2f::Zero();
  if (pinhole_) return {intrinsics_.fx / depth, intrinsics_.fy / depth};
  return {cols_per_rad_ / depth, 1.0F / (mean_row_spacing_rad_ * depth)};
}

}  // namespace flat2d::maps::range3d
