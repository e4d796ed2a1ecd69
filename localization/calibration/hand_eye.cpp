#include "localization/calibration/hand_eye.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>

#include "hal/common/angles.hpp"

namespace flat2d::localization::calibration {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Jacobian = Eigen::Matrix<double, 6, 6>;

constexpr double kDifferenceStep = 1e-6;

// x, y, z (m), roll, pitch, yaw (rad) -> vehicle_T_sensor, Z-Y-X as maps::VehicleFromSensor.
Eigen::Isometry3d PoseOf(const Vector6& theta) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = theta.head<3>();
  pose.linear() = (Eigen::AngleAxisd(theta[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(theta[4], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(theta[3], Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

Vector6 ParametersOf(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d& r = pose.linear();
  Vector6 theta;
  theta.head<3>() = pose.translation();
  theta[3] = std::atan2(r(2, 1), r(2, 2));
  theta[4] = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  theta[5] = std::atan2(r(1, 0), r(0, 0));
  return theta;
}

// Eq. 6.3's term, whitened: the sensor's measured motion against the one the vehicle's
// motion predicts through P (Eq. 6.2).
Vector6 WhitenedError(const MotionPair& pair, const Eigen::Isometry3d& vehicle_T_sensor, const HandEyeOptions& options) {
  const Eigen::Isometry3d predicted = vehicle_T_sensor.inverse() * pair.vehicle_motion * vehicle_T_sensor;
  const Eigen::Isometry3d error = pair.sensor_motion.inverse() * predicted;
  const Eigen::AngleAxisd rotation(error.rotation());
  Vector6 e;
  e.head<3>() = error.translation() / options.sigma_translation_m;
  e.tail<3>() = rotation.angle() * rotation.axis() / options.sigma_rotation_rad;
  return e;
}

Jacobian NumericJacobian(const MotionPair& pair, const Vector6& theta, const HandEyeOptions& options) {
  Jacobian j;
  for (int k = 0; k < 6; ++k) {
    Vector6 plus = theta, minus = theta;
    plus[k] += kDifferenceStep;
    minus[k] -= kDifferenceStep;
    if (options.fixed[static_cast<std::size_t>(k)]) {
      j.col(k).setZero();
      continue;
    }
    j.col(k) = (WhitenedError(pair, PoseOf(plus), options) - WhitenedError(pair, PoseOf(minus), options)) / (2.0 * kDifferenceStep);
  }
  return j;
}

// Huber while the guess is still far; then the pairs beyond the threshold there (failed
// registrations, wheel slip) are left out and the rest solved by plain least squares, as a
// Huber kernel alone still lets a tenth of the pairs 1 m off pull the rotation by a tenth
// of a degree. The set is fixed for the second stage, so that it converges.
enum class Kernel { kHuber, kInliersOnly };

double Weight(double norm, double threshold, Kernel kernel) {
  return kernel == Kernel::kInliersOnly || norm <= threshold ? 1.0 : threshold / norm;
}

struct NormalEquations {
  Matrix6 h = Matrix6::Zero();
  Vector6 g = Vector6::Zero();
  double chi2 = 0.0;  // robust
};

// Over the pairs whose `used` is set.
NormalEquations Linearize(std::span<const MotionPair> pairs, const std::vector<bool>& used, const Vector6& theta,
                          const HandEyeOptions& options, Kernel kernel) {
  NormalEquations n;
  const Eigen::Isometry3d pose = PoseOf(theta);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!used[i]) continue;
    const MotionPair& pair = pairs[i];
    const Vector6 e = WhitenedError(pair, pose, options);
    const double w = Weight(e.norm(), options.huber_threshold, kernel);
    const Jacobian j = NumericJacobian(pair, theta, options);
    n.h.noalias() += w * j.transpose() * j;
    n.g.noalias() += w * j.transpose() * e;
    n.chi2 += w * e.squaredNorm();
  }
  return n;
}

// The information, Jacobi-scaled so that metres and radians compare, split into its
// constrained eigen-directions and the rest.
struct ScaledInformation {
  Vector6 scale;  // theta = scale .* scaled theta
  Matrix6 directions;
  Vector6 eigenvalues;
  Eigen::Array<bool, 6, 1> constrained;
  Eigen::Array<bool, 6, 1> observable;  // per component: the unconstrained directions hold less than half of it
};

ScaledInformation Decompose(const Matrix6& h, const HandEyeOptions& options) {
  ScaledInformation s;
  // A component with next to no information keeps a modest scale: blown up to unit
  // information, its rounding noise would leak into the constrained directions.
  const double floor = h.diagonal().maxCoeff() * options.null_eigenvalue_share;
  s.scale = h.diagonal().cwiseMax(floor).cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(s.scale.asDiagonal() * h * s.scale.asDiagonal());
  s.directions = eigen.eigenvectors();
  s.eigenvalues = eigen.eigenvalues();
  s.constrained = s.eigenvalues.array() > options.null_eigenvalue_share * s.eigenvalues.maxCoeff();
  Vector6 null_share = Vector6::Zero();
  for (int k = 0; k < 6; ++k) {
    if (!s.constrained[k]) null_share += s.directions.col(k).cwiseAbs2();
  }
  s.observable = null_share.array() < 0.5;
  return s;
}

// The Gauss-Newton step within the constrained directions; unobservable components keep
// the guess exactly.
Vector6 Step(const ScaledInformation& s, const Vector6& g) {
  const Vector6 scaled_g = s.scale.cwiseProduct(g);
  Vector6 step = Vector6::Zero();
  for (int k = 0; k < 6; ++k) {
    if (s.constrained[k]) step -= s.directions.col(k) * (s.directions.col(k).dot(scaled_g) / s.eigenvalues[k]);
  }
  return s.observable.select(s.scale.cwiseProduct(step), Vector6::Zero());
}

// Observability and 1-sigma per component from the pseudo-inverse, the covariance scaled by
// the errors' variance factor (the sigmas assumed in the options are only a guess).
void Uncertainty(const ScaledInformation& s, double variance_factor, HandEyeResult& result) {
  Matrix6 covariance = Matrix6::Zero();
  for (int k = 0; k < 6; ++k) {
    const Vector6& v = s.directions.col(k);
    if (s.constrained[k]) covariance += v * v.transpose() / s.eigenvalues[k];
  }
  covariance = s.scale.asDiagonal() * covariance * s.scale.asDiagonal() * variance_factor;
  for (int k = 0; k < 6; ++k) {
    result.observable[static_cast<std::size_t>(k)] = s.observable[k];
    const double sigma = std::sqrt(std::max(covariance(k, k), 0.0)) * (k >= 3 ? kRadToDeg : 1.0);
    result.sigma[static_cast<std::size_t>(k)] = result.observable[static_cast<std::size_t>(k)] ? sigma : 0.0;
  }
}

// The pairs within the threshold of `pose`.
std::vector<bool> Inliers(std::span<const MotionPair> pairs, const Eigen::Isometry3d& pose, const HandEyeOptions& options) {
  std::vector<bool> inliers(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) inliers[i] = WhitenedError(pairs[i], pose, options).norm() <= options.huber_threshold;
  return inliers;
}

void Residuals(std::span<const MotionPair> pairs, const std::vector<bool>& inliers, const Eigen::Isometry3d& pose,
               const HandEyeOptions& options, HandEyeResult& result) {
  double translation = 0.0, rotation = 0.0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!inliers[i]) continue;
    const Vector6 e = WhitenedError(pairs[i], pose, options);
    ++result.inliers;
    translation += (e.head<3>() * options.sigma_translation_m).squaredNorm();
    rotation += (e.tail<3>() * options.sigma_rotation_rad).squaredNorm();
  }
  const double n = std::max(result.inliers, 1);
  result.rms_translation_m = std::sqrt(translation / n);
  result.rms_rotation_deg = std::sqrt(rotation / n) * kRadToDeg;
}

bool Finite(const Eigen::Isometry3d& pose) { return pose.matrix().allFinite(); }

// One solve with options.fixed held at the initial values.
Result<HandEyeResult> Solve(std::span<const MotionPair> pairs, const Eigen::Isometry3d& initial_vehicle_T_sensor,
                            const HandEyeOptions& options) {
  HandEyeResult result;
  result.pairs = static_cast<int>(pairs.size());
  Vector6 theta = ParametersOf(initial_vehicle_T_sensor);
  std::vector<bool> used(pairs.size(), true);
  NormalEquations n = Linearize(pairs, used, theta, options, Kernel::kHuber);
  // Under 1 (whitened error per metre or radian): no component is known to within 1 m or 1 rad.
  if (!(n.h.diagonal().maxCoeff() >= 1.0)) {
    return MakeError("hand-eye calibration: the motions constrain no component (did the vehicle move?)");
  }
  ScaledInformation information = Decompose(n.h, options);
  for (const Kernel kernel : {Kernel::kHuber, Kernel::kInliersOnly}) {
    if (kernel == Kernel::kInliersOnly) {
      used = Inliers(pairs, PoseOf(theta), options);
      const auto agreeing = std::count(used.begin(), used.end(), true);
      if (agreeing < options.min_pairs) {
        return MakeError("hand-eye calibration: only " + std::to_string(agreeing) + " of " + std::to_string(pairs.size()) +
                         " sensor motions agree with the odometry's through any mounting near the guess (did the tracking fail?)");
      }
    }
    n = Linearize(pairs, used, theta, options, kernel);
    information = Decompose(n.h, options);
    for (int i = 0; i < options.max_iterations; ++i) {
      const Vector6 step = Step(information, n.g);
      theta += step;
      ++result.iterations;
      n = Linearize(pairs, used, theta, options, kernel);
      information = Decompose(n.h, options);
      if (information.scale.cwiseInverse().cwiseProduct(step).norm() < options.convergence_step) break;
    }
  }
  result.vehicle_T_sensor = PoseOf(theta);
  Residuals(pairs, used, result.vehicle_T_sensor, options, result);
  const double dof = std::max(6.0 * result.inliers - 6.0, 1.0);
  Uncertainty(information, n.chi2 / dof, result);
  return result;
}

}  // namespace

Result<HandEyeResult> SolveHandEye(std::span<const MotionPair> pairs, const Eigen::Isometry3d& initial_vehicle_T_sensor,
                                   const HandEyeOptions& options) {
  if (std::ssize(pairs) < options.min_pairs) {
    return MakeError("hand-eye calibration: " + std::to_string(pairs.size()) + " motion pairs, fewer than " +
                     std::to_string(options.min_pairs) + ": drive further, with turns");
  }
  if (!Finite(initial_vehicle_T_sensor)) return MakeError("hand-eye calibration: the initial mounting is not finite");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!Finite(pairs[i].sensor_motion) || !Finite(pairs[i].vehicle_motion)) {
      return MakeError("hand-eye calibration: motion pair " + std::to_string(i) + " is not finite");
    }
  }
  // Components the drive barely constrains (x and y on a straight drive, where only the
  // gyro's noise turns the vehicle) would come out metres off: held at the guess instead,
  // the worst first (its uncertainty inflates the ones it correlates with), one solve
  // after another, until every free one is known within the limits.
  HandEyeOptions held = options;
  for (;;) {
    auto result = Solve(pairs, initial_vehicle_T_sensor, held);
    if (!result.ok()) return result;
    std::optional<std::size_t> worst;
    double worst_ratio = 1.0;
    for (std::size_t c = 0; c < 6; ++c) {
      const double ratio = result->sigma[c] / (c < 3 ? options.max_sigma_m : options.max_sigma_deg);
      if (!held.fixed[c] && result->observable[c] && ratio > worst_ratio) {
        worst = c;
        worst_ratio = ratio;
      }
    }
    if (!worst) return result;
    held.fixed[*worst] = true;
  }
}

double OdometryDistanceScale(std::span<const MotionPair> pairs, double max_angle_rad) {
  std::vector<double> ratios;
  for (const MotionPair& pair : pairs) {
    const double distance = pair.vehicle_motion.translation().norm();
    if (distance <= 0.0 || Eigen::AngleAxisd(pair.vehicle_motion.rotation()).angle() >= max_angle_rad) continue;
    ratios.push_back(pair.sensor_motion.translation().norm() / distance);
  }
  if (ratios.empty()) return 1.0;
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
  return ratios[ratios.size() / 2];
}

std::vector<MotionPair> MotionPairs(std::span<const Eigen::Isometry3d> world_T_sensor,
                                    std::span<const Eigen::Isometry3d> odometry_T_vehicle, double min_distance_m,
                                    double min_angle_rad) {
  std::vector<MotionPair> pairs;
  const std::size_t n = std::min(world_T_sensor.size(), odometry_T_vehicle.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = i + 1;
    for (; j < n; ++j) {
      const Eigen::Isometry3d motion = odometry_T_vehicle[i].inverse() * odometry_T_vehicle[j];
      if (motion.translation().norm() >= min_distance_m || Eigen::AngleAxisd(motion.rotation()).angle() >= min_angle_rad) break;
    }
    if (j >= n) break;
    pairs.push_back({world_T_sensor[i].inverse() * world_T_sensor[j], odometry_T_vehicle[i].inverse() * odometry_T_vehicle[j]});
  }
  return pairs;
}

}  // namespace flat2d::localization::calibration
