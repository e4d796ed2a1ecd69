#include "localization/odometry/can_odometry.hpp"

#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization {

CanOdometry::CanOdometry(hal::can::OdometryMapper mapper, DeadReckoning dead_reckoning,
                         PoseHistory history, bool heading_from_wheels)
    : mapper_(std::move(mapper)),
      dead_reckoning_(std::move(dead_reckoning)),
      history_(std::move(history)),
      heading_from_wheels_(heading_from_wheels) {}

Result<CanOdometry> CanOdometry::Create(const hal::can::Dbc& dbc, const OdometryConfig& config,
                                        const PoseHistoryOptions& history_options) {
  Result<hal::can::OdometryMapper> mapper = hal::can::OdometryMapper::Create(dbc, config.mapping());
  if (!mapper.ok()) return mapper.error();
  Result<DeadReckoningOptions> options = DeadReckoningOptionsFrom(config.dead_reckoning());
  if (!options.ok()) return options.error();
  Result<DeadReckoning> dead_reckoning = DeadReckoning::Create(*options);
  if (!dead_reckoning.ok()) return dead_reckoning.error();
  Result<PoseHistory> history = PoseHistory::Create(history_options);
  if (!history.ok()) return history.error();
  return CanOdometry(std::move(mapper).value(), std::move(dead_reckoning).value(),
                     std::move(history).value(), config.dead_reckoning().heading_from_wheels());
}

std::optional<DeadReckoningUpdate> CanOdometry::Push(const hal::can::CanFrame& frame) {
  if (!mapper_.Map(frame, measurement_)) return std::nullopt;
  // With heading from the wheels, the yaw-rate sensor is not consulted at all (D2).
  if (heading_from_wheels_) measurement_.yaw_rate_radps.reset();
  if (!measurement_.wheel_speeds && !measurement_.vehicle_speed_mps && !measurement_.yaw_rate_radps) {
    return std::nullopt;  // steering only: nothing to integrate
  }
  DeadReckoningUpdate update = dead_reckoning_.Update(measurement_);
  if (update.new_sample()) history_.Push(update.sample);
  return update;
}

}  // namespace flat2d::localization
