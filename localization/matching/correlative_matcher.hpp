// Correlative scan matching of a 2D structure scan against a 2D map (Olson 2009,
// "Real-time correlative scan matching"; thesis 7.2): the exact best pose of a discretized
// search window, found by branch and bound over a max-pooled score pyramid, refined below
// the grid, with a covariance read off the score surface.
//
// Two uses, one call: tracking (a window of about +-1.5 m and +-6 deg around the pose
// odometry predicts) and global relocalization (a window of tens of metres and all
// headings: any half-angle >= pi). Steps of Match: (1) check the input; (2) choose the
// headings (Olson's angular step for the farthest point) and rotate the scan once per
// heading (rotated_scans.hpp); (3) branch and bound (branch_and_bound.hpp), or every
// candidate in MatchExhaustive, the reference the tests compare against; (4) refine and
// estimate the covariance (score_surface.hpp); (5) judge: score threshold, distinct second
// peak. All storage is sized in the constructor from MatcherLimits, so SetMap and Match
// allocate nothing; a map or window beyond the limits is refused with a status.
#pragma once

#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "localization/matching/branch_and_bound.hpp"
#include <memory>

#include "localization/matching/match_grid.hpp"
#include "localization/matching/match_map.hpp"
#include "localization/matching/match_result.hpp"
#include "localization/matching/scan_points.hpp"
#include "localization/matching/rotated_scans.hpp"
#include "localization/matching/score_pyramid.hpp"
#include "localization/matching/score_surface.hpp"
#include "localization/matching/score_table.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

// The bounds every buffer is sized by.
struct MatcherLimits {
  std::size_t max_points = 2000;           // scan points per match
  std::size_t max_map_cells = 1000 * 1000;  // width * height of the map
  int max_window_cells = 64;               // half-width of the translation window, cells
  int max_headings = 512;                  // headings per search
  int max_levels = 8;                      // pyramid levels incl. the table (block 2^(n-1))
};

struct MatcherOptions {
  ScoreTableOptions table;
  SurfaceOptions surface;
  double min_score = 0.4;         // fraction of points on structure for kOk
  std::size_t min_points = 10;    // fewer points: kTooFewPoints
  double angular_step = 0.0;      // radians between headings; 0: Olson's rule per scan...
  double step_range_cap = 30.0;   // ...for the farthest point, or this range if nearer (m):
                                  // farther points move a little more than a cell per step,
                                  // which the blur and the refinement absorb
  int refine_iterations = 10;     // Levenberg-Marquardt steps below the grid; 0: none
  // A distinct peak (farther than the separations below) scoring at least this fraction of
  // the best makes the match kAmbiguous; 0 disables the check.
  double ambiguity_ratio = 0.0;
  double ambiguity_separation_m = 0.5;
  double ambiguity_separation_rad = 0.1;
};

// Global relocalization in two stages (Relocalize): a complete but coarse search of the
// whole window, then a tracking match at full detail around its best.
struct RelocalizationOptions {
  double decimation_m = 0.5;       // stage 1: one point per square this size
  double step_range_cap_m = 3.0;   // stage 1: headings stepped for points this far away
  double refine_linear_m = 0.5;    // stage 2: tracking window around stage 1's best
  double refine_angular_rad = 0.05;
};

// Half-widths of the search window around the prediction.
struct SearchWindow {
  double linear = 1.5;    // metres, in x and in y
  double angular = 0.105;  // radians; >= pi searches all headings
};

class CorrelativeMatcher {
 public:
  CorrelativeMatcher(const MatcherLimits& limits, const MatcherOptions& options);

  // Rasterizes `map` into the score table and pyramid (in place, no allocation).
  Status SetMap(const MatchGrid& map);
  bool has_map() const { return map_->built(); }
  // A spare of the matcher's size, to build elsewhere and exchange (allocates: call it when
  // the matcher is made, not while matching).
  std::unique_ptr<MatchMap> NewMap() const;
  // Matches against `built` from now on (it must come from NewMap); returns the previous map.
  std::unique_ptr<MatchMap> ExchangeMap(std::unique_ptr<MatchMap> built);

  // Matches `points` (vehicle frame) around map_T_vehicle `prediction`.
  MatchResult Match(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                    const SearchWindow& window);
  // Global relocalization (a window of tens of metres, all headings) in two stages: (1) the
  // scan decimated to relocalization.decimation_m and headings stepped for
  // step_range_cap_m, so that the exact branch and bound scores far fewer points and
  // headings (stage 1 still searches every pose of the window, at coarser steps); (2) Match
  // of the full scan in a small window around stage 1's best. The result is stage 2's,
  // with the candidates and headings of both stages; a stage-1 failure is returned as is.
  MatchResult Relocalize(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                         const SearchWindow& window, const RelocalizationOptions& relocalization = {});
  // The same with an exhaustive search (tests, small windows).
  MatchResult MatchExhaustive(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                              const SearchWindow& window);

  const ScoreTable& table() const { return map_->table(); }
  const MatcherLimits& limits() const { return limits_; }

 private:
  MatchResult Search(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                     const SearchWindow& window, bool exhaustive, double step_range_cap);
  MatchStatus CheckInput(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                         const SearchWindow& window) const;
  SearchProblem Prepare(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                        const SearchWindow& window, double step_range_cap, HeadingSet& headings);
  void Judge(std::span<const Eigen::Vector2d> points, const SearchOutcome& outcome,
             MatchResult& result) const;

  MatcherLimits limits_;
  MatcherOptions options_;
  std::unique_ptr<MatchMap> map_;
  RotatedScans scans_;
  BranchAndBound branch_and_bound_;
  ScanPoints coarse_scan_;  // Relocalize's stage 1: limits.max_points
};

}  // namespace flat2d::localization
