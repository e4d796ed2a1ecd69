// MapBuilder: the odometry scale (see map_builder.hpp, "Odometry scale").
#include "localization/mapping/map_builder.hpp"

namespace flat2d::localization::mapping {

Se2 MapBuilder::ScaledStep(const Se2& step) const { return Se2(scale_ * step.translation(), step.theta()); }

void MapBuilder::UpdateScale(const Se2& odometry_step, const Se2& matched_step, const Eigen::Matrix3d& information) {
  if (!options_.estimate_odometry_scale) return;
  if (!scale_estimate_.Add(odometry_step, matched_step, information) || !scale_estimate_.ready()) return;
  scale_ = scale_estimate_.scale();
  stats_.odometry_scale = scale_;
}

void MapBuilder::RescaleOdometryFactors() {
  for (std::size_t i = 0; i < odometry_factors_.size(); ++i) {
    const Se2 step = ScaledStep(keyframes_[i].odometry.Inverse() * keyframes_[i + 1].odometry);
    graph::BetweenFactor& factor = graph_.betweens[odometry_factors_[i]];
    factor.measurement = step;
    factor.information = OdometryInformation(step, options_.odometry);
  }
}

}  // namespace flat2d::localization::mapping
