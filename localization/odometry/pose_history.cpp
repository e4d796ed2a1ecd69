#include "localization/odometry/pose_history.hpp"

#include <string>

namespace flat2d::localization {
namespace {

bool Answered(QueryStatus status) {
  return status == QueryStatus::kInWindow || status == QueryStatus::kExtrapolated;
}

}  // namespace

Status ValidateOptions(const PoseHistoryOptions& options) {
  if (options.capacity < 2) {
    return MakeError("PoseHistoryOptions.capacity must be at least 2, got " +
                     std::to_string(options.capacity));
  }
  if (options.max_extrapolation_ns < 0) {
    return MakeError("PoseHistoryOptions.max_extrapolation_ns must be non-negative, got " +
                     std::to_string(options.max_extrapolation_ns));
  }
  return Status::Ok();
}

Result<PoseHistory> PoseHistory::Create(const PoseHistoryOptions& options) {
  if (Status status = ValidateOptions(options); !status.ok()) return status.error();
  return PoseHistory(options);
}

PoseHistory::PoseHistory(const PoseHistoryOptions& options)
    : options_(options), ring_(options.capacity) {}

bool PoseHistory::Push(const OdometrySample& sample) {
  if (size_ > 0 && sample.time_ns <= newest_ns()) {
    ++stats_.not_newer;
    return false;
  }
  if (size_ == ring_.size()) {
    ring_[oldest_] = sample;
    oldest_ = (oldest_ + 1) % ring_.size();
    ++stats_.evicted;
  } else {
    ring_[(oldest_ + size_) % ring_.size()] = sample;
    ++size_;
  }
  ++stats_.pushed;
  return true;
}

void PoseHistory::Clear() {
  oldest_ = 0;
  size_ = 0;
}

TimeNs PoseHistory::oldest_ns() const { return size_ == 0 ? 0 : Sample(0).time_ns; }

TimeNs PoseHistory::newest_ns() const { return size_ == 0 ? 0 : Sample(size_ - 1).time_ns; }

const OdometrySample& PoseHistory::Sample(std::size_t index) const {
  return ring_[(oldest_ + index) % ring_.size()];
}

PoseHistory::Location PoseHistory::Locate(TimeNs time_ns) const {
  Location location;
  if (size_ == 0) return location;
  if (time_ns < oldest_ns()) {
    location.status = QueryStatus::kBeforeWindow;
    location.outside_by_ns = oldest_ns() - time_ns;
    return location;
  }
  // The newest sample at or before time_ns: binary search over the ring in time order.
  std::size_t low = 0;
  std::size_t high = size_;  // invariant: Sample(low) <= time_ns < Sample(high)
  while (high - low > 1) {
    const std::size_t middle = low + (high - low) / 2;
    (Sample(middle).time_ns <= time_ns ? low : high) = middle;
  }
  location.index = low;
  const TimeNs since = time_ns - Sample(low).time_ns;
  if (low + 1 < size_) {
    location.status = QueryStatus::kInWindow;
    location.s = static_cast<double>(since) /
                 static_cast<double>(Sample(low + 1).time_ns - Sample(low).time_ns);
    return location;
  }
  if (since == 0) {
    location.status = QueryStatus::kInWindow;
    return location;
  }
  location.outside_by_ns = since;
  const bool can_extrapolate =
      since <= options_.max_extrapolation_ns && size_ >= 2 && !Sample(low).discontinuity;
  location.status = can_extrapolate ? QueryStatus::kExtrapolated : QueryStatus::kAfterWindow;
  if (can_extrapolate) {
    location.s = static_cast<double>(since) /
                 static_cast<double>(Sample(low).time_ns - Sample(low - 1).time_ns);
  }
  return location;
}

PoseHistory::Step PoseHistory::StepAfter(std::size_t index) const {
  Step step;
  if (size_ < 2) return step;
  if (index + 1 >= size_) index = size_ - 2;  // extrapolation repeats the last step
  const OdometrySample& from = Sample(index);
  const OdometrySample& to = Sample(index + 1);
  step.twist = (from.local_T_vehicle.Inverse() * to.local_T_vehicle).Log();
  step.covariance = to.step_covariance;
  step.discontinuity = to.discontinuity;
  return step;
}

PoseAtTime PoseHistory::At(TimeNs time_ns) const {
  const Location location = Locate(time_ns);
  PoseAtTime result;
  result.status = location.status;
  result.outside_by_ns = location.outside_by_ns;
  if (!Answered(location.status)) return result;
  const OdometrySample& base = Sample(location.index);
  result.local_T_vehicle = base.local_T_vehicle;
  result.covariance = base.covariance;
  if (location.s > 0.0) {  // H1
    const Step step = StepAfter(location.index);
    const Se2 partial = Se2::Exp(location.s * step.twist);
    result.covariance = ComposeCovariance(base.local_T_vehicle, base.covariance, partial,
                                          location.s * step.covariance);
    result.local_T_vehicle = base.local_T_vehicle * partial;
  }
  return result;
}

RelativeMotion PoseHistory::Between(TimeNs a_ns, TimeNs b_ns) const {
  const Location a = Locate(a_ns);
  const Location b = Locate(b_ns);
  for (const Location* location : {&a, &b}) {
    if (!Answered(location->status)) {
      RelativeMotion refused;
      refused.status = location->status;
      refused.outside_by_ns = location->outside_by_ns;
      return refused;
    }
  }
  if (a_ns <= b_ns) return Chain(a, b);
  RelativeMotion motion = Chain(b, a);  // b_T_a; invert it with E6
  const Eigen::Matrix3d j = InverseJacobian(motion.a_T_b);
  motion.covariance = j * motion.covariance * j.transpose();
  motion.a_T_b = motion.a_T_b.Inverse();
  return motion;
}

RelativeMotion PoseHistory::Chain(const Location& a, const Location& b) const {
  RelativeMotion motion;
  const bool extrapolated =
      a.status == QueryStatus::kExtrapolated || b.status == QueryStatus::kExtrapolated;
  motion.status = extrapolated ? QueryStatus::kExtrapolated : QueryStatus::kInWindow;
  motion.outside_by_ns = b.status == QueryStatus::kExtrapolated ? b.outside_by_ns : 0;
  // H2: compose each (partial) step after a, starting from zero covariance.
  const auto add = [&motion](const Se2& step, const Eigen::Matrix3d& covariance, bool jump) {
    motion.covariance = ComposeCovariance(motion.a_T_b, motion.covariance, step, covariance);
    motion.a_T_b = motion.a_T_b * step;
    motion.spans_discontinuity = motion.spans_discontinuity || jump;
  };
  const auto add_part = [&](std::size_t index, double from_s, double to_s) {
    if (to_s <= from_s) return;
    const Step step = StepAfter(index);
    const double part = to_s - from_s;
    add(Se2::Exp(part * step.twist), part * step.covariance, step.discontinuity);
  };
  if (a.index == b.index) {
    add_part(a.index, a.s, b.s);
    return motion;
  }
  add_part(a.index, a.s, 1.0);
  for (std::size_t k = a.index + 1; k < b.index; ++k) {
    const OdometrySample& to = Sample(k + 1);
    add(Sample(k).local_T_vehicle.Inverse() * to.local_T_vehicle, to.step_covariance,
        to.discontinuity);
  }
  add_part(b.index, 0.0, b.s);
  return motion;
}

}  // namespace flat2d::localization
