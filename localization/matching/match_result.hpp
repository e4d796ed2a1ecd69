// What a scan match returns: the pose, how sure it is, and why it failed when it did.
//
// The covariance is estimated from the score surface around the peak (see
// score_surface.hpp), so it is large along directions the scene does not constrain (a
// corridor's axis) and small across them; a fusion back end uses it as the match factor's
// uncertainty. Failures are values, never exceptions or aborts: a daemon that meets a bad
// revolution counts it and carries on with odometry.
#pragma once

#include <cstdint>
#include <string_view>

#include <Eigen/Core>

#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

enum class MatchStatus {
  kOk,
  kNoMap,                // no map was loaded
  kInvalidInput,         // a non-finite point or prediction, a bad window, too many points
  kTooFewPoints,         // fewer points than options.min_points
  kOutsideMap,           // the predicted position is not on the map
  kScoreBelowThreshold,  // the best candidate has too few points on structure
  kAmbiguous,            // a distinct second peak scores nearly as well as the best
};

std::string_view MatchStatusName(MatchStatus status);

struct MatchResult {
  MatchStatus status = MatchStatus::kNoMap;
  Se2 map_T_vehicle;  // refined pose (the prediction when nothing was searched)
  // Covariance of (x, y, theta), x and y along the map axes (se2.hpp's convention).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  double score = 0.0;              // fraction of points on structure at the best grid pose, 0..1
  double second_peak_score = 0.0;  // best distinct peak found during the search, 0..1
  std::uint64_t evaluated_candidates = 0;  // leaves and bounds scored
  int headings = 0;                // headings searched
  std::size_t points = 0;          // points matched
  double angular_step = 0.0;       // radians between searched headings

  bool ok() const { return status == MatchStatus::kOk; }
};

}  // namespace flat2d::localization
