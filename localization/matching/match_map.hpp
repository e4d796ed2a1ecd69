// A map as the correlative matcher scores against it: the score table and its branch-and-
// bound pyramid, built together from one MatchGrid. Sized once from the matcher's limits, so
// a rebuild allocates nothing. The matcher holds one; a localizer can build a second on
// another thread while the first is matched, and exchange them (CorrelativeMatcher::
// ExchangeMap). Not movable: the pyramid points at the table beside it.
#pragma once

#include <cstddef>

#include "hal/common/error.hpp"
#include "localization/matching/match_grid.hpp"
#include "localization/matching/score_pyramid.hpp"
#include "localization/matching/score_table.hpp"

namespace flat2d::localization {

class MatchMap {
 public:
  MatchMap(std::size_t max_cells, int max_levels, const ScoreTableOptions& options)
      : table_(max_cells, options), pyramid_(max_cells, max_levels) {}
  MatchMap(const MatchMap&) = delete;
  MatchMap& operator=(const MatchMap&) = delete;

  // Rasterizes `map` into the table, then the pyramid; not built() after an error.
  Status Rebuild(const MatchGrid& map) {
    built_ = false;
    if (Status status = table_.Rebuild(map); !status) return status;
    if (Status status = pyramid_.Rebuild(table_); !status) return status;
    built_ = true;
    return Status::Ok();
  }

  bool built() const { return built_; }
  const ScoreTable& table() const { return table_; }
  const ScorePyramid& pyramid() const { return pyramid_; }

 private:
  ScoreTable table_;
  ScorePyramid pyramid_;
  bool built_ = false;
};

}  // namespace flat2d::localization
