#include "localization/graph/se2_factors.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace flat2d::localization::graph {
namespace {

// log(w |L|^(1/2)): the log of a component's peak likelihood up to the shared (2 pi)^(-3/2).
double LogPeak(const MixtureComponent& component) {
  return std::log(component.weight) + 0.5 * std::log(component.information.determinant());
}

}  // namespace

Se2 Retract(const Se2& pose, const Eigen::Vector3d& delta) {
  return Se2(pose.x() + delta.x(), pose.y() + delta.y(), pose.theta() + delta.z());
}

Eigen::Vector3d BetweenError(const Se2& pose_i, const Se2& pose_j, const Se2& measurement,
                             AngleResidual angle) {
  const Eigen::Vector2d local = pose_i.Rotation().transpose() *
                                (pose_j.translation() - pose_i.translation());
  const Eigen::Vector2d e_t =
      measurement.Rotation().transpose() * (local - measurement.translation());
  const double dtheta = NormalizeAngle(pose_j.theta() - pose_i.theta() - measurement.theta());
  const double e_theta = angle == AngleResidual::kWrapped ? dtheta : 2.0 * std::sin(0.5 * dtheta);
  return {e_t.x(), e_t.y(), e_theta};
}

BetweenLinearization LinearizeBetween(const Se2& pose_i, const Se2& pose_j,
                                      const Se2& measurement, AngleResidual angle) {
  const Eigen::Matrix2d rz_ri = measurement.Rotation().transpose() * pose_i.Rotation().transpose();
  const Eigen::Vector2d d = pose_j.translation() - pose_i.translation();
  const Eigen::Vector2d s_d(-d.y(), d.x());  // S d
  const double dtheta = NormalizeAngle(pose_j.theta() - pose_i.theta() - measurement.theta());

  BetweenLinearization lin;
  lin.error.head<2>() = rz_ri * d - measurement.Rotation().transpose() * measurement.translation();
  double angle_slope = 1.0;
  if (angle == AngleResidual::kWrapped) {
    lin.error.z() = dtheta;
  } else {
    lin.error.z() = 2.0 * std::sin(0.5 * dtheta);
    angle_slope = std::cos(0.5 * dtheta);
  }
  // F3.
  lin.jacobian_i.setZero();
  lin.jacobian_i.topLeftCorner<2, 2>() = -rz_ri;
  lin.jacobian_i.block<2, 1>(0, 2) = -rz_ri * s_d;
  lin.jacobian_i(2, 2) = -angle_slope;
  lin.jacobian_j.setZero();
  lin.jacobian_j.topLeftCorner<2, 2>() = rz_ri;
  lin.jacobian_j(2, 2) = angle_slope;
  return lin;
}

Eigen::Vector3d PriorError(const Se2& pose, const Se2& measurement) {
  return ComponentDifference(pose, measurement);
}

MaxMixture MakeNullHypothesisMixture(const Eigen::Matrix3d& match_information, double null_weight,
                                     double null_information_scale) {
  MaxMixture mixture;
  mixture.components[0] = {1.0 - null_weight, match_information};
  mixture.components[1] = {null_weight, match_information * null_information_scale};
  mixture.size = 2;
  return mixture;
}

MixtureChoice SelectMixtureComponent(const MaxMixture& mixture, const Eigen::Vector3d& error) {
  assert(mixture.size >= 1 && mixture.size <= kMaxMixtureComponents);
  double best_log_peak = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < mixture.size; ++k) {
    best_log_peak = std::max(best_log_peak, LogPeak(mixture.components[k]));
  }
  MixtureChoice choice;
  choice.cost = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < mixture.size; ++k) {
    const MixtureComponent& component = mixture.components[k];
    const double offset = 2.0 * (best_log_peak - LogPeak(component));
    const double cost = error.dot(component.information * error) + offset;  // F5
    if (cost < choice.cost) {
      choice.component = k;
      choice.information = component.information;
      choice.offset = offset;
      choice.cost = cost;
    }
  }
  return choice;
}

}  // namespace flat2d::localization::graph
