#include "localization/landmarks/plane.hpp"

#include <cmath>

#include "localization/landmarks/so3.hpp"

namespace flat2d::localization::landmarks {

namespace {

// A normal whose horizontal part is shorter than this is at the pole (phi = 0 or pi):
// its azimuth is rounding noise, so the conversion fixes it to 0.
constexpr double kPoleRadius = 1e-12;

}  // namespace

std::optional<Plane> PlaneFromCoefficients(const Eigen::Vector4d& abcd) {
  if (!abcd.allFinite()) return std::nullopt;
  const double norm = abcd.head<3>().norm();
  if (norm < 1e-12) return std::nullopt;
  return Plane{abcd.head<3>() / norm, abcd(3) / norm};  // A.20-A.23
}

Eigen::Vector4d Coefficients(const Plane& plane) {
  Eigen::Vector4d abcd;
  abcd << plane.normal, plane.distance;
  return abcd;
}

PlaneAngles ToAngles(const Plane& plane) {
  const Eigen::Vector3d& n = plane.normal;
  const double horizontal = std::hypot(n.x(), n.y());
  PlaneAngles angles;
  angles.azimuth = horizontal < kPoleRadius ? 0.0 : std::atan2(n.y(), n.x());  // A.25
  angles.elevation = std::atan2(horizontal, n.z());                             // A.26
  angles.distance = plane.distance;
  return angles;
}

Plane FromAngles(const PlaneAngles& angles) {
  const double s = std::sin(angles.elevation);
  const Eigen::Vector3d normal(s * std::cos(angles.azimuth), s * std::sin(angles.azimuth),
                               std::cos(angles.elevation));
  return Plane{normal, angles.distance};
}

Plane Transformed(const Eigen::Isometry3d& a_T_b, const Plane& plane_b) {
  // x_b = R^T (x_a - t) in n_b . x_b + d_b = 0 gives (R n_b) . x_a + d_b - (R n_b) . t = 0.
  const Eigen::Vector3d normal = a_T_b.linear() * plane_b.normal;
  return Plane{normal, plane_b.distance - normal.dot(a_T_b.translation())};
}

Plane Retract(const Plane& plane, const Eigen::Vector3d& delta) {
  const Eigen::Vector3d v = TangentBasis(plane.normal) * delta.head<2>();
  const double angle = v.norm();
  // sin|v| / |v| -> 1; below 1e-12 its series differs from 1 by less than rounding.
  const double sinc = angle < 1e-12 ? 1.0 : std::sin(angle) / angle;
  Eigen::Vector3d normal = std::cos(angle) * plane.normal + sinc * v;
  // Exact on paper; renormalizing keeps repeated updates from drifting off the sphere.
  normal.normalize();
  return Plane{normal, plane.distance + delta(2)};
}

Eigen::Vector3d Local(const Plane& from, const Plane& to) {
  const Eigen::Vector3d& n = from.normal;
  const Eigen::Vector3d tangent = to.normal - n.dot(to.normal) * n;
  const double angle = std::atan2(tangent.norm(), n.dot(to.normal));
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  if (tangent.norm() > 0.0) delta.head<2>() = TangentBasis(n).transpose() * tangent * (angle / tangent.norm());
  delta(2) = to.distance - from.distance;
  return delta;
}

}  // namespace flat2d::localization::landmarks
