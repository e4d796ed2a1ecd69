// The lookup table of correlative scan matching (Olson 2009, "Real-time correlative scan
// matching", section III): the map rasterized once so that scoring a candidate pose is a
// sum of table lookups, one per scan point.
//
// A cell's score is exp(-d^2 / (2 sigma^2)) with d the distance from the cell to the
// nearest structure cell, truncated at d > 3 sigma: the maximum, not the sum, of Gaussian
// kernels placed on the structure, so that a point exactly on structure scores 1 however
// dense the map is and the total score divided by the point count is the fraction of points
// on structure. The blur gives the search a smooth basin (points that miss by a cell still
// count) and models the point noise. Steps of Rebuild: (1) per row, the squared distance to
// the nearest structure cell within the kernel radius; (2) per column, the minimum of
// dy^2 + that (the separable exact truncated distance transform); (3) the kernel of the
// squared distance, quantized to 0..kMaxCellScore. Storage is fixed at construction from
// the largest map to be used, so a new map tile is loaded in place without allocating.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "localization/matching/match_grid.hpp"

namespace flat2d::localization {

inline constexpr int kMaxCellScore = 255;

struct ScoreTableOptions {
  double sigma_cells = 1.5;    // kernel standard deviation, in cells
  double radius_sigmas = 3.0;  // the kernel is zero beyond this many sigmas
};

class ScoreTable {
 public:
  // Storage for maps up to max_cells cells (width * height).
  explicit ScoreTable(std::size_t max_cells, ScoreTableOptions options = {});

  // Rasterizes `grid`; fails (table unchanged) when it has more than max_cells cells.
  Status Rebuild(const MatchGrid& grid);

  const GridGeometry& geometry() const { return geometry_; }
  int width() const { return geometry_.width; }
  int height() const { return geometry_.height; }
  // Score of cell (x, y); 0 outside the map.
  int At(int x, int y) const {
    return geometry_.Contains(x, y) ? cells_[static_cast<std::size_t>(y) * stride_ + x] : 0;
  }
  // Bilinear interpolation between cell centres, in units of kMaxCellScore.
  double Interpolate(double cell_x, double cell_y) const;
  // (value, d value / d cell_x, d value / d cell_y) of the bilinear interpolation.
  Eigen::Vector3d InterpolateWithGradient(double cell_x, double cell_y) const;
  const std::uint8_t* data() const { return cells_.data(); }
  std::size_t max_cells() const { return cells_.size(); }

 private:
  void RowDistances(const MatchGrid& grid, int radius);
  void ColumnDistancesToScores(int radius);

  ScoreTableOptions options_;
  GridGeometry geometry_;
  std::size_t stride_ = 0;
  std::vector<std::uint8_t> cells_;          // max_cells
  std::vector<std::uint16_t> row_distance_;  // max_cells, squared distance along rows
  std::vector<std::uint16_t> min_row_;       // one output row of the column pass
  std::vector<std::uint8_t> kernel_;         // score by squared distance 0..(radius^2 * 2)
};

}  // namespace flat2d::localization
