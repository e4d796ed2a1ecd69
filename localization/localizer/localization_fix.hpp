// The localizer's estimate as a value: the newest solved node and L2G (LocalizationFix),
// which another thread can copy, and the pose at any time composed from it and odometry.
#pragma once

#include <Eigen/Core>

#include "hal/common/time.hpp"
#include "localization/localizer/localizer_state.hpp"
#include "localization/odometry/pose_history.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

// The estimate at one time: global_T_vehicle = L2G x local_T_vehicle.
struct GlobalPose {
  bool ok = false;  // false: no fix (initializing), or no odometry at that time
  TimeNs time_ns = 0;
  Se2 global_T_vehicle;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // (x, y, theta), se2.hpp's convention
  LocalizerState state = LocalizerState::kInitializing;
};

// What PoseAt needs from the localizer, as a value another thread can hold: the daemon's
// API thread serves poses from a copy of this and of the odometry history (daemon/service).
struct LocalizationFix {
  bool has_fix = false;  // the graph holds a node
  TimeNs node_ns = 0;    // the newest node's time
  Se2 node_pose;         // global_T_vehicle there, solved
  Eigen::Matrix3d node_covariance = Eigen::Matrix3d::Zero();
  Se2 global_T_local;    // L2G
  LocalizerState state = LocalizerState::kInitializing;
  TimeNs last_accepted_ns = 0;  // the newest accepted match's time; 0: none yet
};

// global_T_vehicle at `time_ns` = node pose x odometry from the node's time, its covariance
// composed from both (se2.hpp E5); not ok without a fix or outside the odometry's window.
GlobalPose ComposeGlobalPose(const LocalizationFix& fix, const PoseHistory& odometry, TimeNs time_ns);

}  // namespace flat2d::localization
