// Seeded random poses, directions and planes for the landmark tests, and the
// central-difference Jacobian the analytic ones are held to. Built from first principles
// (Gram-Schmidt, cross products) rather than from the library's own helpers, so a mistake
// there cannot cancel out in a test.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

namespace flat2d::localization::landmarks::testing {

// The translation scale of random case i: every third case is far from the origin (up to
// 1 km), where rounding in the Jacobians is largest.
inline double TranslationScale(int i) { return i % 3 == 0 ? 1e3 : 10.0; }

inline Eigen::Vector3d RandomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Braces: the draws are made in order (a call's arguments have none).
  return scale * Eigen::Vector3d{unit(rng), unit(rng), unit(rng)};
}

inline Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d v{gauss(rng), gauss(rng), gauss(rng)};
  while (v.norm() < 1e-3) v = Eigen::Vector3d{gauss(rng), gauss(rng), gauss(rng)};
  return v.normalized();
}

// A unit vector orthogonal to `unit`, by Gram-Schmidt of a random vector.
inline Eigen::Vector3d RandomOrthogonal(std::mt19937& rng, const Eigen::Vector3d& unit) {
  Eigen::Vector3d v = RandomUnit(rng);
  while ((v - unit.dot(v) * unit).norm() < 1e-3) v = RandomUnit(rng);
  return (v - unit.dot(v) * unit).normalized();
}

// A uniformly random rotation (normalized Gaussian quaternion) and a translation in a cube
// of half-side `translation_scale`.
inline Eigen::Isometry3d RandomPose(std::mt19937& rng, double translation_scale) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Quaterniond q{gauss(rng), gauss(rng), gauss(rng), gauss(rng)};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = RandomVector(rng, translation_scale);
  return pose;
}

// The rotation of `angle` about `axis` (unit), as a pose.
inline Eigen::Isometry3d Rotation(const Eigen::Vector3d& axis, double angle) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  return pose;
}

// d error(x [+] step) / d step at step = 0 by central differences of width h.
template <int Rows, int Cols, typename ErrorAt>
Eigen::Matrix<double, Rows, Cols> CentralDifference(const ErrorAt& error_at, double h) {
  Eigen::Matrix<double, Rows, Cols> jacobian;
  for (int k = 0; k < Cols; ++k) {
    Eigen::Matrix<double, Cols, 1> step = Eigen::Matrix<double, Cols, 1>::Zero();
    step(k) = h;
    jacobian.col(k) = (error_at(step) - error_at(-step)) / (2.0 * h);
  }
  return jacobian;
}

// |analytic - numeric| within `tolerance` of the larger of 1 and the numeric Jacobian's
// largest entry: relative for the large entries a far pose gives, absolute near zero.
template <typename Matrix>
bool JacobiansAgree(const Matrix& analytic, const Matrix& numeric, double tolerance) {
  const double scale = std::max(1.0, numeric.cwiseAbs().maxCoeff());
  return (analytic - numeric).cwiseAbs().maxCoeff() <= tolerance * scale;
}

}  // namespace flat2d::localization::landmarks::testing
