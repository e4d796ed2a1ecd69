#include "hal/velodyne/azimuth_cut.hpp"

#include <cmath>
#include <numbers>

namespace flat2d::hal::velodyne {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kWrapThresholdRad = std::numbers::pi / 2.0;

double WrapPositive(double angle) {
  angle = std::fmod(angle, kTwoPi);
  return angle < 0.0 ? angle + kTwoPi : angle;
}

}  // namespace

AzimuthCut::AzimuthCut(double cut_azimuth_rad) : cut_azimuth_rad_(WrapPositive(cut_azimuth_rad)) {}

AzimuthStep AzimuthCut::Next(float azimuth_rad) {
  const double relative = WrapPositive(static_cast<double>(azimuth_rad) - cut_azimuth_rad_);
  const double step = relative - previous_relative_rad_;
  AzimuthStep result;
  result.wraps = have_previous_ && step < -kWrapThresholdRad;
  if (have_previous_ && !result.wraps && step > 0.0 && step < kWrapThresholdRad) result.forward_step_rad = step;
  previous_relative_rad_ = relative;
  have_previous_ = true;
  return result;
}

}  // namespace flat2d::hal::velodyne
