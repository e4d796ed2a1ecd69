// The L2G localizer's options (localizer.hpp says what each stage does with them) and
// their validation; flat2dd and flat2d-localize fill them from localizer_config.proto.
#pragma once

#include <cstddef>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "localization/graph/sliding_window.hpp"
#include "localization/localizer/map_window.hpp"
#include "localization/matching/correlative_matcher.hpp"

namespace flat2d::localization {

struct LocalizerOptions {
  MapWindowOptions map_window;
  // Prepare the next mosaic window on a worker thread (map_prefetch.hpp); false: every move
  // fills the window and rebuilds the score table on the tracking thread. A replay is
  // repeatable either way; the prefetch costs a second window and score table in memory.
  bool map_prefetch = true;
  // Track against the viewpoint sub-map nearest the prediction (thesis 7.3.2: structure
  // hidden from the mapping drive's pose cannot attract the match) instead of the mosaic.
  // Global relocalization always searches the mosaic. Without viewpoints in the map: the mosaic.
  bool match_viewpoints = false;
  double point_range_m = 35.0;       // slammable cells farther away are not matched (a 50 m grid's corners)
  double decimation_m = 0.1;         // one point per square this size
  std::size_t max_grid_points = 60'000;  // slammable cells read from one grid
  std::size_t max_scan_points = 3'000;   // matched per revolution (decimated further to fit)
  SearchWindow tracking_window{1.0, 0.1};
  // Tracking: a match counts when this share of the scan's points, and at least this many,
  // land on the map's structure. The share is kept low on purpose: on a sparse street the
  // few poles and trunks match while the cars alongside (slammable, not in the map) do not,
  // and the campus drive spends seconds at 10-25 matched points of 100-250. The count, the
  // match covariance and the max-mixture against the odometry decide instead.
  double min_score = 0.02;
  std::size_t min_matched_points = 8;
  // Until a match has confirmed an initial pose, a tracking match must score this much: in
  // a building, a pose metres off still puts a fifth of the scan on some wall.
  double confirm_min_score = 0.3;
  // While DEGRADED the search widens to three standard deviations of the predicted
  // position, up to this (it must fit the matcher's window: relocalization_max_radius_m).
  double max_tracking_window_m = 3.0;
  // Floors on the match's standard deviations: the score surface of a sharp scene says
  // millimetres, which would let one revolution's grid noise outweigh the odometry.
  double min_match_sigma_m = 0.02;
  double min_match_sigma_rad = 0.002;
  // Added to the odometry's own covariance between nodes, per metre driven: dead reckoning's
  // covariance models white noise, but a tyre radius or yaw-rate bias a few tenths of a
  // percent off is systematic, and an odometry factor that ignored it would outweigh the
  // matches and drag the estimate behind them.
  double odometry_sigma_per_m = 0.01;       // of the step's length
  double odometry_sigma_rad_per_m = 0.001;  // of the heading
  graph::NullHypothesis null_hypothesis{.weight = 0.05, .information_scale = 1e-3};
  graph::SlidingWindowOptions graph{.capacity = 100};
  int solve_iterations = 5;
  TimeNs degraded_after_ns = 500 * kNsPerMs;
  // LOST: no accepted match for lost_after (a sparse stretch of road may go seconds without
  // one while odometry holds the pose), or the position more uncertain than lost_sigma_m,
  // or, after an initial pose, no match confirming it within initial_lost_after (the pose
  // was wrong: relocalize at once).
  TimeNs lost_after_ns = 5 * kNsPerSecond;
  TimeNs initial_lost_after_ns = 1 * kNsPerSecond;
  double lost_sigma_m = 1.0;
  // Relocalization: all headings within a radius that starts here (after tracking was
  // lost: at three standard deviations of the position, at least max_tracking_window_m)
  // and grows by the factor after each failed revolution, up to the maximum.
  double relocalization_radius_m = 10.0;
  double relocalization_growth = 1.5;
  double relocalization_max_radius_m = 20.0;
  // A global match must score this much, with at least relocalization_min_matched_points
  // on structure, and its best distinct other peak may score at most
  // relocalization_max_peak_ratio of it: a search in a repetitive corridor must not pick
  // one of two lookalikes, and a sparse street's true pose scores low but stands out.
  double relocalization_min_score = 0.1;
  std::size_t relocalization_min_matched_points = 25;
  double relocalization_max_peak_ratio = 0.85;
  // A global match is on probation: the state stays LOST until this many tracking matches
  // in a row are accepted after it, and the first rejected one resumes the search.
  int relocalization_confirmations = 3;
  RelocalizationOptions relocalization;
  int map_cache_tiles = 64;  // the prior map reader's LRU cache
};

Status ValidateOptions(const LocalizerOptions& options);

}  // namespace flat2d::localization
