#include "localization/tools/drift.hpp"

#include <cmath>
#include <optional>

#include "hal/common/angles.hpp"
#include "localization/odometry/se2.hpp"
#include "maps/grid/interpolated_poses.hpp"

namespace flat2d::localization::tools {

Drift DriftAgainst(const std::vector<evaluation::TimedPose>& reference,
                   const std::vector<hal::trajectory::StampedPose>& trajectory) {
  constexpr double kMaxGapS = 1.0;  // between reference poses (the truth is at 200 Hz)
  Drift drift;
  std::optional<Eigen::Vector2d> last;
  for (const hal::trajectory::StampedPose& p : trajectory) {
    Se2 truth;
    if (!evaluation::PoseAt(reference, static_cast<double>(p.time_ns) * 1e-9, kMaxGapS, truth)) continue;
    const maps::StampedPose2d estimate = maps::Flatten(p.time_ns, p.world_T_body);
    if (last) drift.distance_m += (truth.translation() - *last).norm();
    last = truth.translation();
    ++drift.poses;
    drift.end_error_m = (estimate.position - truth.translation()).norm();
    drift.max_error_m = std::max(drift.max_error_m, drift.end_error_m);
    drift.end_heading_error_deg = std::abs(NormalizeAngle(estimate.yaw - truth.theta())) * kRadToDeg;
  }
  return drift;
}

}  // namespace flat2d::localization::tools
