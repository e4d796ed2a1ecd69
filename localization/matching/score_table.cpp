#include "localization/matching/score_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace flat2d::localization {
namespace {

constexpr std::uint16_t kFar = std::numeric_limits<std::uint16_t>::max();

int KernelRadius(const ScoreTableOptions& options) {
  return std::max(1, static_cast<int>(std::floor(options.radius_sigmas * options.sigma_cells)));
}

}  // namespace

ScoreTable::ScoreTable(std::size_t max_cells, ScoreTableOptions options)
    : options_(options),
      cells_(max_cells, 0),
      row_distance_(max_cells, kFar),
      min_row_(max_cells, kFar) {
  const int radius = KernelRadius(options_);
  kernel_.resize(static_cast<std::size_t>(radius * radius) + 1);
  const double sigma = options_.sigma_cells;
  for (std::size_t d2 = 0; d2 < kernel_.size(); ++d2) {
    const double score = kMaxCellScore * std::exp(-static_cast<double>(d2) / (2.0 * sigma * sigma));
    kernel_[d2] = static_cast<std::uint8_t>(std::lround(score));
  }
}

Status ScoreTable::Rebuild(const MatchGrid& grid) {
  if (grid.geometry().CellCount() > cells_.size()) {
    return MakeError("score table: map of " + std::to_string(grid.geometry().CellCount()) +
                     " cells exceeds the preallocated " + std::to_string(cells_.size()));
  }
  geometry_ = grid.geometry();
  stride_ = static_cast<std::size_t>(geometry_.width);
  const int radius = KernelRadius(options_);
  RowDistances(grid, radius);
  ColumnDistancesToScores(radius);
  return Status::Ok();
}

// Step 1: squared distance to the nearest structure cell of the same row, kFar beyond
// `radius`, from one left-to-right and one right-to-left sweep.
void ScoreTable::RowDistances(const MatchGrid& grid, int radius) {
  const int width = geometry_.width;
  for (int y = 0; y < geometry_.height; ++y) {
    std::uint16_t* row = row_distance_.data() + static_cast<std::size_t>(y) * stride_;
    int since = radius + 1;  // cells since the last structure cell, saturated
    for (int x = 0; x < width; ++x) {
      since = grid.Occupied(x, y) ? 0 : std::min(since + 1, radius + 1);
      row[x] = since <= radius ? static_cast<std::uint16_t>(since * since) : kFar;
    }
    since = radius + 1;
    for (int x = width - 1; x >= 0; --x) {
      since = grid.Occupied(x, y) ? 0 : std::min(since + 1, radius + 1);
      if (since <= radius) row[x] = std::min(row[x], static_cast<std::uint16_t>(since * since));
    }
  }
}

// Steps 2 and 3, a row of output at a time so that every access runs along memory.
void ScoreTable::ColumnDistancesToScores(int radius) {
  const int width = geometry_.width;
  const int height = geometry_.height;
  const int max_d2 = radius * radius;
  for (int y = 0; y < height; ++y) {
    std::fill_n(min_row_.begin(), width, kFar);
    for (int dy = -radius; dy <= radius; ++dy) {
      if (y + dy < 0 || y + dy >= height) continue;
      const std::uint16_t* row = row_distance_.data() + static_cast<std::size_t>(y + dy) * stride_;
      const int dy2 = dy * dy;
      for (int x = 0; x < width; ++x) {
        if (row[x] == kFar) continue;
        const int d2 = dy2 + row[x];
        if (d2 < min_row_[x]) min_row_[x] = static_cast<std::uint16_t>(d2);
      }
    }
    std::uint8_t* out = cells_.data() + static_cast<std::size_t>(y) * stride_;
    for (int x = 0; x < width; ++x) {
      out[x] = min_row_[x] <= max_d2 ? kernel_[min_row_[x]] : 0;
    }
  }
}

double ScoreTable::Interpolate(double cell_x, double cell_y) const {
  const double u = cell_x - 0.5;
  const double v = cell_y - 0.5;
  if (!(std::abs(u) < 1.0e9 && std::abs(v) < 1.0e9)) return 0.0;
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int x0 = static_cast<int>(fu);
  const int y0 = static_cast<int>(fv);
  const double ax = u - fu;
  const double ay = v - fv;
  const double bottom = (1.0 - ax) * At(x0, y0) + ax * At(x0 + 1, y0);
  const double top = (1.0 - ax) * At(x0, y0 + 1) + ax * At(x0 + 1, y0 + 1);
  return (1.0 - ay) * bottom + ay * top;
}

Eigen::Vector3d ScoreTable::InterpolateWithGradient(double cell_x, double cell_y) const {
  const double u = cell_x - 0.5;
  const double v = cell_y - 0.5;
  if (!(std::abs(u) < 1.0e9 && std::abs(v) < 1.0e9)) return Eigen::Vector3d::Zero();
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int x0 = static_cast<int>(fu);
  const int y0 = static_cast<int>(fv);
  const double ax = u - fu;
  const double ay = v - fv;
  const double v00 = At(x0, y0);
  const double v10 = At(x0 + 1, y0);
  const double v01 = At(x0, y0 + 1);
  const double v11 = At(x0 + 1, y0 + 1);
  const double bottom = (1.0 - ax) * v00 + ax * v10;
  const double top = (1.0 - ax) * v01 + ax * v11;
  return {(1.0 - ay) * bottom + ay * top,
          (1.0 - ay) * (v10 - v00) + ay * (v11 - v01), top - bottom};
}

}  // namespace flat2d::localization
