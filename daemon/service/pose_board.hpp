// What the API thread serves, written by the localization thread (DESIGN.md "Threads"):
// the localizer's fix (localizer.hpp LocalizationFix), a copy of the odometry history it
// composes poses with, and the health figures of the status reply.
//
// The localization thread pushes each new odometry sample and the fix after every input;
// the API thread composes global_T_vehicle = node pose x odometry at any time in the
// window (issue 10 item 2: pose at a timestamp, from odometry history). One mutex guards
// both sides and is held for a sample copy or one pose composition, never for a match, so
// a pose query waits microseconds at most. The history is sized once, at Create.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

#include "hal/common/error.hpp"
#include "localization/localizer/localizer.hpp"
#include "localization/odometry/pose_history.hpp"

namespace flat2d::daemon {

// Figures the localization thread publishes once per revolution (and the sources' counts).
struct HealthFigures {
  std::uint64_t revolutions = 0;
  std::uint64_t matches_accepted = 0;
  std::uint64_t matches_rejected = 0;
  std::uint64_t relocalizations = 0;
  std::uint64_t map_errors = 0;
  double match_ms_p50 = 0.0;
  double match_ms_p99 = 0.0;
  double solve_ms_p50 = 0.0;
  double solve_ms_p99 = 0.0;
  std::uint32_t graph_nodes = 0;
  std::uint64_t lidar_malformed = 0;
  std::uint64_t can_malformed = 0;
  TimeNs newest_datagram_ns = 0;  // sensor clock
  TimeNs newest_frame_ns = 0;
  std::uint64_t can_frames = 0;  // taken by the pipeline, from the CAN thread or the followed log
};

// A pose and the fix it was composed from, read under one lock: a reply's L2G and time since
// the last match belong to its pose even while the localization thread publishes a new fix.
struct ServedPose {
  localization::GlobalPose pose;
  localization::LocalizationFix fix;
};

class PoseBoard {
 public:
  static Result<PoseBoard> Create(const localization::PoseHistoryOptions& history);

  // Localization thread.
  void PushOdometry(const localization::OdometrySample& sample);
  void PublishFix(const localization::LocalizationFix& fix);
  void PublishHealth(const HealthFigures& health);
  void ClearOdometry();  // the pipeline was rebuilt (reload): its odometry frame is new

  // API thread: the pose at `time_ns`, or at the newest odometry sample.
  localization::GlobalPose PoseAt(TimeNs time_ns) const { return ServeAt(time_ns).pose; }
  localization::GlobalPose PoseNow() const { return ServeNow().pose; }
  ServedPose ServeAt(TimeNs time_ns) const;
  ServedPose ServeNow() const;
  // Where `time_ns` falls in the odometry window (the out-of-window error says how far off).
  localization::PoseAtTime OdometryAt(TimeNs time_ns) const;
  localization::LocalizationFix fix() const;
  HealthFigures health() const;
  TimeNs newest_odometry_ns() const;

  PoseBoard(PoseBoard&& other) noexcept;

 private:
  explicit PoseBoard(localization::PoseHistory history) : history_(std::move(history)) {}

  mutable std::mutex mutex_;
  localization::PoseHistory history_;
  localization::LocalizationFix fix_;
  HealthFigures health_;
};

}  // namespace flat2d::daemon
