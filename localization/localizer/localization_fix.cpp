#include "localization/localizer/localization_fix.hpp"

namespace flat2d::localization {

GlobalPose ComposeGlobalPose(const LocalizationFix& fix, const PoseHistory& odometry, TimeNs time_ns) {
  GlobalPose pose;
  pose.time_ns = time_ns;
  pose.state = fix.state;
  if (!fix.has_fix) return pose;
  const RelativeMotion motion = odometry.Between(fix.node_ns, time_ns);
  if (!motion.ok()) return pose;
  pose.ok = true;
  pose.global_T_vehicle = fix.node_pose * motion.a_T_b;
  pose.covariance = ComposeCovariance(fix.node_pose, fix.node_covariance, motion.a_T_b, motion.covariance);
  return pose;
}

}  // namespace flat2d::localization
