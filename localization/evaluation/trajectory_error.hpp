// Absolute trajectory error (Sturm et al. 2012, the TUM benchmark's ATE) in the plane: the
// estimate is sampled at each reference time (interpolated, relations.hpp's PoseAt), the
// rigid motion that best overlays the sampled positions on the reference is found in
// closed form (the 2D case of Horn's method, no scale), and the position differences after
// it are summarized, also split along and across the reference's heading (issue 9's
// lateral and longitudinal figures). Headings are compared after the same rotation.
#pragma once

#include <cstddef>
#include <vector>

#include "localization/evaluation/relations.hpp"

namespace flat2d::localization::evaluation {

// Nearest-rank percentiles of a non-negative error.
struct ErrorPercentiles {
  double p50 = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
};

// ... of `values` (sorted here); all 0 when empty. The tools' CPU figures use it too.
ErrorPercentiles PercentilesOf(std::vector<double> values);

// The heading error's distribution as the thesis plots it (Fig. 7.10): |error| in bins of
// kHeadingBinRad, the last bin holding everything beyond.
inline constexpr double kHeadingBinRad = 0.005;
inline constexpr std::size_t kHeadingBins = 21;  // 0 .. 0.1 rad, then the rest

struct TrajectoryError {
  std::size_t poses = 0;      // reference poses the estimate covers
  std::size_t unmatched = 0;  // reference poses it does not
  Se2 reference_T_estimate;   // the alignment (identity with align = false)
  double rmse_m = 0.0;
  double mean_m = 0.0;
  double median_m = 0.0;
  double max_m = 0.0;
  double rotation_rmse_deg = 0.0;
  // Position error split in the reference's frame: along its heading (longitudinal) and
  // across it (lateral); the magnitudes' percentiles.
  ErrorPercentiles position_m, longitudinal_m, lateral_m;
  // Heading: the share of poses within 0.02 and 0.025 rad of the reference, the worst
  // |error|, the histogram.
  double heading_within_0_02 = 0.0;
  double heading_within_0_025 = 0.0;
  double heading_worst_rad = 0.0;
  std::vector<std::size_t> heading_histogram = std::vector<std::size_t>(kHeadingBins, 0);
};

TrajectoryError EvaluateTrajectory(const std::vector<TimedPose>& estimate, const std::vector<TimedPose>& reference,
                                   bool align = true, double max_gap_s = 1.0);

}  // namespace flat2d::localization::evaluation
