// The odometry history: a fixed-capacity ring of dead-reckoned samples (time,
// local_T_vehicle, covariance, step covariance), queried at any timestamp in its window.
//
// Between neighbours k and k+1 the vehicle moves with the constant body twist
// xi = Log(p_k^-1 p_k+1) (se2.hpp E3), so at s = (t - t_k) / (t_k+1 - t_k)
//   p(t) = p_k Exp(s xi),  P(t) = J_a P_k J_a^T + J_b (s Q_k+1) J_b^T   (E5),          (H1)
// Q_k+1 the step covariance; white input noise makes a step's covariance grow linearly
// in time, and H1 equals P_k+1 at s = 1, so the covariance is continuous along the window.
// The motion between two times is the chain of the (partial) steps between them, each
// composed with E5 starting from zero covariance at the first time:                     (H2)
//   a_T_b = p(t_a)^-1 p(t_b),  cost O(samples between t_a and t_b).
// Up to max_extrapolation_ns past the newest sample, H1 continues with the last step's
// twist and covariance rate (never across a discontinuity); earlier than the oldest
// sample or later than that, the answer is kBeforeWindow or kAfterWindow with the
// distance to the window. Storage is allocated once, at Create; nothing allocates after.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "localization/odometry/odometry_sample.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

struct PoseHistoryOptions {
  // Samples kept. The bound: odometry rate x the longest look-back, e.g. the factor
  // graph's window. 4096 holds 20 s at 200 Hz (~800 KB).
  std::size_t capacity = 4096;
  // How far past the newest sample H1 may extrapolate; 0 disables. 50 ms covers a
  // LiDAR revolution ending between two CAN frames of a 20 Hz odometry message.
  TimeNs max_extrapolation_ns = 50 * kNsPerMs;
};

Status ValidateOptions(const PoseHistoryOptions& options);

enum class QueryStatus : std::uint8_t {
  kInWindow,      // interpolated between samples, or exactly on one
  kExtrapolated,  // after the newest sample, within max_extrapolation_ns
  kBeforeWindow,  // earlier than the oldest sample: no answer
  kAfterWindow,   // later than the newest sample plus the extrapolation limit: no answer
  kEmpty,         // no samples yet
};

struct PoseAtTime {
  QueryStatus status = QueryStatus::kEmpty;
  Se2 local_T_vehicle;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // as OdometrySample::covariance
  // For kBeforeWindow: oldest time - t; for kExtrapolated and kAfterWindow: t - newest time.
  TimeNs outside_by_ns = 0;
  bool ok() const {
    return status == QueryStatus::kInWindow || status == QueryStatus::kExtrapolated;
  }
};

struct RelativeMotion {
  QueryStatus status = QueryStatus::kEmpty;  // the worse of the two times
  Se2 a_T_b;
  // Of (x, y, theta) of a_T_b, x and y along a's axes (se2.hpp).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  TimeNs outside_by_ns = 0;          // of the time that set the status
  bool spans_discontinuity = false;  // an unmeasured step lies between the two times
  bool ok() const {
    return status == QueryStatus::kInWindow || status == QueryStatus::kExtrapolated;
  }
};

struct PoseHistoryStats {
  std::uint64_t pushed = 0;
  std::uint64_t not_newer = 0;  // samples not after the newest: refused
  std::uint64_t evicted = 0;    // oldest samples overwritten by a full ring
};

class PoseHistory {
 public:
  static Result<PoseHistory> Create(const PoseHistoryOptions& options);

  // Appends a sample strictly newer than the newest, evicting the oldest when full.
  // Returns false (and counts) otherwise.
  bool Push(const OdometrySample& sample);
  void Clear();

  PoseAtTime At(TimeNs time_ns) const;                     // H1
  RelativeMotion Between(TimeNs a_ns, TimeNs b_ns) const;  // H2: a_T_b

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return ring_.size(); }
  TimeNs oldest_ns() const;  // 0 when empty
  TimeNs newest_ns() const;  // 0 when empty
  const PoseHistoryStats& stats() const { return stats_; }

 private:
  // Where a time falls: on the step after sample `index`, at fraction s of it (s > 1
  // past the newest sample when extrapolating).
  struct Location {
    QueryStatus status = QueryStatus::kEmpty;
    std::size_t index = 0;
    double s = 0.0;
    TimeNs outside_by_ns = 0;
  };
  // The step after sample `index` (the last real step, when `index` is the newest).
  struct Step {
    Eigen::Vector3d twist = Eigen::Vector3d::Zero();       // per unit s
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // at s = 1
    bool discontinuity = false;
  };

  explicit PoseHistory(const PoseHistoryOptions& options);

  const OdometrySample& Sample(std::size_t index) const;  // 0 = oldest
  Location Locate(TimeNs time_ns) const;
  Step StepAfter(std::size_t index) const;
  RelativeMotion Chain(const Location& a, const Location& b) const;

  PoseHistoryOptions options_;
  PoseHistoryStats stats_;
  std::vector<OdometrySample> ring_;  // capacity samples, sized at Create
  std::size_t oldest_ = 0;            // ring index of the oldest sample
  std::size_t size_ = 0;
};

}  // namespace flat2d::localization
