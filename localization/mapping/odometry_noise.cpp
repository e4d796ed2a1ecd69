#include "localization/mapping/odometry_noise.hpp"

#include <cmath>
#include <random>

namespace flat2d::localization::mapping {
namespace {

constexpr double kMinSigmaM = 0.005;
constexpr double kMinSigmaRad = 0.002;

}  // namespace

std::vector<Se2> CorruptOdometry(const std::vector<Se2>& reference, const OdometryNoiseModel& model) {
  std::vector<Se2> noisy;
  if (reference.empty()) return noisy;
  std::mt19937_64 random(model.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double scale = 1.0 + model.scale_sigma * normal(random);
  noisy.push_back(reference.front());
  for (std::size_t i = 1; i < reference.size(); ++i) {
    const Se2 step = reference[i - 1].Inverse() * reference[i];
    const double d = step.translation().norm();
    const double forward = step.x() * scale + model.translation_fraction * d * normal(random);
    const double lateral = step.y() * scale + model.lateral_fraction * d * normal(random);
    const double sigma_theta = model.rotation_fraction * std::abs(step.theta()) + model.rotation_per_metre * d;
    const double heading = step.theta() + sigma_theta * normal(random);
    noisy.push_back(noisy.back() * Se2(forward, lateral, heading));
  }
  return noisy;
}

Eigen::Matrix3d OdometryInformation(const Se2& step, const OdometryNoiseModel& model) {
  const double d = step.translation().norm();
  const double sigma_x = std::max(kMinSigmaM, (model.translation_fraction + model.scale_sigma) * d);
  const double sigma_y = std::max(kMinSigmaM, (model.lateral_fraction + model.scale_sigma) * d);
  const double sigma_theta =
      std::max(kMinSigmaRad, model.rotation_fraction * std::abs(step.theta()) + model.rotation_per_metre * d);
  return Eigen::Vector3d(1.0 / (sigma_x * sigma_x), 1.0 / (sigma_y * sigma_y), 1.0 / (sigma_theta * sigma_theta))
      .asDiagonal();
}

}  // namespace flat2d::localization::mapping
