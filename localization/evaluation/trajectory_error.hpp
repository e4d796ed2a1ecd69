// Absolute trajectory error (Sturm et al. 2012, the TUM benchmark's ATE) in the plane: the
// estimate is sampled at each reference time (interpolated, relations.hpp's PoseAt), the
// rigid motion that best overlays the sampled positions on the reference is found in
// closed form (the 2D case of Horn's method, no scale), and the position differences after
// it are summarized. Headings are compared after the same rotation.
#pragma once

#include <cstddef>
#include <vector>

#include "localization/evaluation/relations.hpp"

namespace flat2d::localization::evaluation {

struct TrajectoryError {
  std::size_t poses = 0;      // reference poses the estimate covers
  std::size_t unmatched = 0;  // reference poses it does not
  Se2 reference_T_estimate;   // the alignment (identity with align = false)
  double rmse_m = 0.0;
  double mean_m = 0.0;
  double median_m = 0.0;
  double max_m = 0.0;
  double rotation_rmse_deg = 0.0;
};

TrajectoryError EvaluateTrajectory(const std::vector<TimedPose>& estimate, const std::vector<TimedPose>& reference,
                                   bool align = true, double max_gap_s = 1.0);

}  // namespace flat2d::localization::evaluation
