// CAN frames to a dead-reckoned trajectory: the odometry front end of flat2dd and of
// `flat2d-can odom`.
//
// Steps per frame: OdometryMapper picks the configured signals (checksums verified) and
// converts them to an OdometryMeasurement; DeadReckoning integrates it on SE(2) with
// covariance; each new sample goes into the fixed-capacity PoseHistory, where poses can be
// queried at any timestamp in the window. Everything is sized at construction.
#pragma once

#include <optional>

#include "hal/can/can_frame.hpp"
#include "hal/can/dbc.hpp"
#include "hal/can/odometry_mapper.hpp"
#include "localization/odometry/dead_reckoning.hpp"
#include "localization/odometry/odometry_config.pb.h"
#include "localization/odometry/pose_history.hpp"

namespace flat2d::localization {

class CanOdometry {
 public:
  static Result<CanOdometry> Create(const hal::can::Dbc& dbc, const OdometryConfig& config,
                                    const PoseHistoryOptions& history = {});

  // Feeds one frame; returns the dead-reckoning update when the frame carried odometry.
  std::optional<DeadReckoningUpdate> Push(const hal::can::CanFrame& frame);

  const hal::can::OdometryMapper& mapper() const { return mapper_; }
  const DeadReckoning& dead_reckoning() const { return dead_reckoning_; }
  const PoseHistory& history() const { return history_; }
  // The last measurement the mapper produced (what the vehicle said, in SI units).
  const hal::can::OdometryMeasurement& last_measurement() const { return measurement_; }

 private:
  CanOdometry(hal::can::OdometryMapper mapper, DeadReckoning dead_reckoning, PoseHistory history,
              bool heading_from_wheels);

  hal::can::OdometryMapper mapper_;
  DeadReckoning dead_reckoning_;
  PoseHistory history_;
  bool heading_from_wheels_;
  hal::can::OdometryMeasurement measurement_;
};

}  // namespace flat2d::localization
