// The odometry's scale (a wheel-radius error) as the least-squares ratio of matched to
// odometry distance along the direction of travel. Only steps a match pins down along the
// path count: in a corridor the match returns the prediction, which would pull the ratio
// towards whatever scale predicted it.
#pragma once

#include <Eigen/Core>

#include "localization/odometry/se2.hpp"

namespace flat2d::localization::mapping {

class OdometryScaleEstimate {
 public:
  // Steps whose match is less sure than max_sigma_m along the path are not used; the
  // scale is kept within 1 +- max_error.
  OdometryScaleEstimate(double max_sigma_m, double max_error);

  // One step: what odometry said, what the match said, and the match's information (in the
  // vehicle frame; the step's turn is small, so it is taken as the step's frame).
  // False if the step was not used.
  bool Add(const Se2& odometry_step, const Se2& matched_step, const Eigen::Matrix3d& information);
  void Reset();

  int steps() const { return steps_; }
  // Enough well-constrained steps for the ratio to be trusted.
  bool ready() const { return steps_ >= kMinSteps; }
  double scale() const;

 private:
  static constexpr int kMinSteps = 20;
  double min_information_;
  double max_error_;
  double numerator_ = 0.0;
  double denominator_ = 0.0;
  int steps_ = 0;
};

}  // namespace flat2d::localization::mapping
