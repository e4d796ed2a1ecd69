#include "localization/landmarks/line.hpp"

#include <cmath>

#include "localization/landmarks/so3.hpp"

namespace flat2d::localization::landmarks {

namespace {

// A direction shorter than this is taken for zero: it has no defined orientation.
constexpr double kMinDirection = 1e-12;

Eigen::Matrix2d Rotation2d(double angle) {
  return Eigen::Rotation2Dd(angle).toRotationMatrix();
}

}  // namespace

std::optional<PluckerLine> LineFromPointDirection(const Eigen::Vector3d& point,
                                                  const Eigen::Vector3d& direction) {
  if (!point.allFinite() || !direction.allFinite()) return std::nullopt;
  const double length = direction.norm();
  if (length < kMinDirection) return std::nullopt;
  const Eigen::Vector3d a = direction / length;
  return PluckerLine{a, a.cross(point)};  // A.13
}

std::optional<PluckerLine> LineFromCoordinates(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (!a.allFinite() || !b.allFinite()) return std::nullopt;
  const double length = a.norm();
  if (length < kMinDirection) return std::nullopt;
  // A moment not orthogonal to the direction belongs to no line (Klein quadric).
  if (std::abs(a.dot(b)) > 1e-9 * length * b.norm()) return std::nullopt;
  return PluckerLine{a / length, b / length};
}

Eigen::Vector3d ClosestPointToOrigin(const PluckerLine& line) {
  // a x b = a x (a x P) = a (a . P) - P |a|^2, so P minus its part along a is b x a / |a|^2.
  return line.b.cross(line.a) / line.a.squaredNorm();
}

Eigen::Vector3d Direction(const PluckerLine& line) { return line.a.normalized(); }

OrthonormalLine ToOrthonormal(const PluckerLine& line) {
  const double a_norm = line.a.norm();
  const Eigen::Vector3d u1 = line.a / a_norm;
  // Gram-Schmidt: b is orthogonal to a up to the rounding of whoever built it.
  const Eigen::Vector3d b_orthogonal = line.b - u1.dot(line.b) * u1;
  const double b_norm = b_orthogonal.norm();
  OrthonormalLine orthonormal;
  // Through the origin (distance below 1e-15 |a|) b / |b| is undefined or noise: any unit
  // vector orthogonal to a completes U, and W = I says the distance is zero.
  const bool through_origin = b_norm < 1e-15 * a_norm;
  const Eigen::Vector3d u2 = through_origin ? Eigen::Vector3d(TangentBasis(u1).col(0))
                                            : Eigen::Vector3d(b_orthogonal / b_norm);
  orthonormal.U.col(0) = u1;
  orthonormal.U.col(1) = u2;
  orthonormal.U.col(2) = u1.cross(u2);  // a x b / |a x b|
  orthonormal.W = Rotation2d(through_origin ? 0.0 : std::atan2(b_norm, a_norm));  // A.15
  return orthonormal;
}

std::optional<PluckerLine> ToPlucker(const OrthonormalLine& line) {
  const double w11 = line.W(0, 0);
  const double w21 = line.W(1, 0);
  if (std::abs(w11) < 1e-12) return std::nullopt;
  // A.16, (w11 u1, w21 u2), divided by w11: the same line with a unit direction.
  return PluckerLine{line.U.col(0), (w21 / w11) * line.U.col(1)};
}

PluckerLine Transformed(const Eigen::Isometry3d& a_T_b, const PluckerLine& line_b) {
  // b_a = (R a_b) x (R P_b + t) = R (a_b x P_b) + (R a_b) x t.
  const Eigen::Vector3d a = a_T_b.linear() * line_b.a;
  return PluckerLine{a, a_T_b.linear() * line_b.b - a_T_b.translation().cross(a)};
}

OrthonormalLine Retract(const OrthonormalLine& line, const Eigen::Vector4d& delta) {
  OrthonormalLine updated;
  updated.U = line.U * ExpSo3(delta.head<3>());  // A.17
  updated.W = line.W * Rotation2d(delta(3));      // A.18
  return updated;
}

Eigen::Vector4d Local(const OrthonormalLine& from, const OrthonormalLine& to) {
  const Eigen::Matrix2d w = from.W.transpose() * to.W;
  Eigen::Vector4d delta;
  delta << LogSo3(from.U.transpose() * to.U), std::atan2(w(1, 0), w(0, 0));
  return delta;
}

}  // namespace flat2d::localization::landmarks
