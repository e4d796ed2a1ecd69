#include "daemon/service/pose_board.hpp"

#include <utility>

namespace flat2d::daemon {

Result<PoseBoard> PoseBoard::Create(const localization::PoseHistoryOptions& history) {
  auto created = localization::PoseHistory::Create(history);
  if (!created.ok()) return created.error();
  return PoseBoard(std::move(*created));
}

PoseBoard::PoseBoard(PoseBoard&& other) noexcept
    : history_(std::move(other.history_)), fix_(other.fix_), health_(other.health_) {}

void PoseBoard::PushOdometry(const localization::OdometrySample& sample) {
  const std::lock_guard lock(mutex_);
  history_.Push(sample);
}

void PoseBoard::PublishFix(const localization::LocalizationFix& fix) {
  const std::lock_guard lock(mutex_);
  fix_ = fix;
}

void PoseBoard::PublishHealth(const HealthFigures& health) {
  const std::lock_guard lock(mutex_);
  health_ = health;
}

void PoseBoard::ClearOdometry() {
  const std::lock_guard lock(mutex_);
  history_.Clear();
  fix_ = {};
}

ServedPose PoseBoard::ServeAt(TimeNs time_ns) const {
  const std::lock_guard lock(mutex_);
  return {localization::ComposeGlobalPose(fix_, history_, time_ns), fix_};
}

ServedPose PoseBoard::ServeNow() const {
  const std::lock_guard lock(mutex_);
  return {localization::ComposeGlobalPose(fix_, history_, history_.newest_ns()), fix_};
}

localization::PoseAtTime PoseBoard::OdometryAt(TimeNs time_ns) const {
  const std::lock_guard lock(mutex_);
  return history_.At(time_ns);
}

localization::LocalizationFix PoseBoard::fix() const {
  const std::lock_guard lock(mutex_);
  return fix_;
}

HealthFigures PoseBoard::health() const {
  const std::lock_guard lock(mutex_);
  return health_;
}

TimeNs PoseBoard::newest_odometry_ns() const {
  const std::lock_guard lock(mutex_);
  return history_.newest_ns();
}

}  // namespace flat2d::daemon
