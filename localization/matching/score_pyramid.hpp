// The multi-resolution tables of branch and bound (Olson 2009, section IV; the
// "precomputation grids" of Hess et al. 2016): level k holds, for each cell (x, y), the
// maximum of the score table over the 2^k x 2^k block whose lowest corner is (x, y).
//
// So for a set of candidate translations that differ by at most 2^k - 1 cells in x and in
// y, summing level k at the lowest translation bounds the score of every candidate in the
// set from above: each point's own lookup can only be one of the block's cells. Level 0 is
// the score table itself. Level k is built from level k - 1 as the maximum of four cells
// 2^(k-1) apart (blocks double each level). All levels are full-size and live in storage
// fixed at construction. Blocks that start left of or below the map are partly inside it;
// Bound() answers them from the block at the map's edge, a superset, so the bound stays
// valid without padding every level.
#pragma once

#include <cstdint>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/matching/score_table.hpp"

namespace flat2d::localization {

class ScorePyramid {
 public:
  // Storage for `max_levels` levels (including level 0, which stays in the table) of maps
  // up to max_cells cells.
  ScorePyramid(std::size_t max_cells, int max_levels);

  // Builds the levels 1..max_levels-1 of `table`. `table` must outlive the pyramid's use.
  Status Rebuild(const ScoreTable& table);

  int levels() const { return max_levels_; }

  // Upper bound of the table over the 2^level block whose lowest corner is (x, y).
  int Bound(int level, int x, int y) const {
    const int block = 1 << level;
    if (x <= -block || y <= -block || x >= width_ || y >= height_) return 0;
    x = x < 0 ? 0 : x;
    y = y < 0 ? 0 : y;
    return Level(level)[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x];
  }

 private:
  const std::uint8_t* Level(int level) const;
  void BuildLevel(int level);

  int max_levels_ = 1;
  std::size_t max_cells_ = 0;
  int width_ = 0;
  int height_ = 0;
  const ScoreTable* table_ = nullptr;
  std::vector<std::uint8_t> levels_;  // (max_levels - 1) * max_cells, level 1 first
};

}  // namespace flat2d::localization
