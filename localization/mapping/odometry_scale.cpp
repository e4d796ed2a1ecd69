#include "localization/mapping/odometry_scale.hpp"

#include <algorithm>

namespace flat2d::localization::mapping {

OdometryScaleEstimate::OdometryScaleEstimate(double max_sigma_m, double max_error)
    : min_information_(1.0 / (max_sigma_m * max_sigma_m)), max_error_(max_error) {}

bool OdometryScaleEstimate::Add(const Se2& odometry_step, const Se2& matched_step,
                                const Eigen::Matrix3d& information) {
  const double distance = odometry_step.translation().norm();
  if (distance < 0.1) return false;  // turning on the spot says nothing of the scale
  const Eigen::Vector2d along = odometry_step.translation() / distance;
  if (along.dot(information.topLeftCorner<2, 2>() * along) < min_information_) return false;
  numerator_ += along.dot(matched_step.translation()) * distance;
  denominator_ += distance * distance;
  ++steps_;
  return true;
}

void OdometryScaleEstimate::Reset() {
  numerator_ = denominator_ = 0.0;
  steps_ = 0;
}

double OdometryScaleEstimate::scale() const {
  if (denominator_ <= 0.0) return 1.0;
  return std::clamp(numerator_ / denominator_, 1.0 - max_error_, 1.0 + max_error_);
}

}  // namespace flat2d::localization::mapping
