// Open-loop drift of a 3D build's trajectory against a reference track, in the plane: what
// `flat2d-map build --mode nicp|landmarks` and flat2d-peer-narf-slam report with --anchor.
#pragma once

#include <vector>

#include "hal/trajectory/tum_file.hpp"
#include "localization/evaluation/relations.hpp"

namespace flat2d::localization::tools {

// Open-loop drift against a reference track (truth, or the anchor) without alignment: both
// start at the same pose, so the error at the end over the reference's distance travelled is
// the drift per metre of a dead-reckoned estimate. In the plane.
struct Drift {
  int poses = 0;            // trajectory poses within the reference's time
  double distance_m = 0.0;  // the reference's path between them
  double end_error_m = 0.0;
  double max_error_m = 0.0;
  double end_heading_error_deg = 0.0;
  double percent() const { return distance_m > 0.0 ? 100.0 * end_error_m / distance_m : 0.0; }
};
Drift DriftAgainst(const std::vector<evaluation::TimedPose>& reference,
                   const std::vector<hal::trajectory::StampedPose>& trajectory);

}  // namespace flat2d::localization::tools
