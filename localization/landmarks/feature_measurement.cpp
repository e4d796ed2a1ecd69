#include "localization/landmarks/feature_measurement.hpp"

#include <cmath>

#include "localization/landmarks/so3.hpp"

namespace flat2d::localization::landmarks {

namespace {

using maps::features3d::LineFeature;
using maps::features3d::PlaneFeature;

// Axes further than this from unit length were not produced by a fit: reject the feature.
constexpr double kUnitTolerance = 1e-3;

bool IsUnit(const Eigen::Vector3d& v) { return v.allFinite() && std::abs(v.norm() - 1.0) < kUnitTolerance; }

template <typename Matrix>
Matrix FiniteOrZero(const Matrix& covariance) {
  return covariance.allFinite() ? covariance : Matrix::Zero();
}

// An axis of the tangent space of `unit`, made exactly orthogonal to it (the fit's axes are
// orthogonal to rounding; the covariance map assumes it).
Eigen::Vector3d OrthogonalPart(const Eigen::Vector3d& axis, const Eigen::Vector3d& unit) {
  return (axis - axis.dot(unit) * unit).normalized();
}

}  // namespace

PlaneFeature TransformedFeature(const Eigen::Isometry3d& a_T_b, const PlaneFeature& feature) {
  PlaneFeature moved = feature;
  moved.normal = a_T_b.linear() * feature.normal;
  moved.centroid = a_T_b * feature.centroid;
  moved.major_axis = a_T_b.linear() * feature.major_axis;
  moved.d = -moved.normal.dot(moved.centroid);
  return moved;
}

LineFeature TransformedFeature(const Eigen::Isometry3d& a_T_b, const LineFeature& feature) {
  LineFeature moved = feature;
  moved.point = a_T_b * feature.point;
  moved.direction = a_T_b.linear() * feature.direction;
  moved.across = a_T_b.linear() * feature.across;
  return moved;
}

std::optional<PlaneMeasurement> PlaneMeasurementOf(const PlaneFeature& feature, const MeasurementFloors& floors) {
  if (!IsUnit(feature.normal) || !IsUnit(feature.major_axis) || !feature.centroid.allFinite() ||
      !std::isfinite(feature.d)) {
    return std::nullopt;
  }
  const Eigen::Vector3d n = feature.normal.normalized();
  const Eigen::Vector3d u3 = OrthogonalPart(feature.major_axis, n);
  if (!u3.allFinite()) return std::nullopt;  // major axis along the normal
  const Eigen::Vector3d u2 = n.cross(u3);
  const Eigen::Matrix<double, 3, 2> basis = TangentBasis(n);
  // The plane through the centroid: d from the fit may differ from -n . c by rounding.
  const Plane plane{n, -n.dot(feature.centroid)};
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();  // M1
  a.block<2, 1>(0, 0) = basis.transpose() * u2;
  a.block<2, 1>(0, 1) = basis.transpose() * u3;
  a(2, 0) = -u2.dot(feature.centroid);
  a(2, 1) = -u3.dot(feature.centroid);
  a(2, 2) = -1.0;
  Eigen::Matrix3d covariance = a * FiniteOrZero(feature.covariance) * a.transpose();
  covariance.diagonal() += Eigen::Vector3d(floors.plane_normal_sigma_rad, floors.plane_normal_sigma_rad,
                                           floors.plane_offset_sigma_m)
                               .cwiseAbs2();
  return PlaneMeasurement{plane, covariance.inverse()};
}

std::optional<LineMeasurement> LineMeasurementOf(const LineFeature& feature, const MeasurementFloors& floors) {
  if (!IsUnit(feature.direction) || !IsUnit(feature.across) || !feature.point.allFinite()) return std::nullopt;
  const Eigen::Vector3d a = feature.direction.normalized();
  const Eigen::Vector3d u1 = OrthogonalPart(feature.across, a);
  if (!u1.allFinite()) return std::nullopt;  // across along the direction
  const std::optional<PluckerLine> line = LineFromPointDirection(feature.point, a);
  if (!line) return std::nullopt;
  Eigen::Matrix<double, 3, 2> u;
  u << u1, a.cross(u1);
  const Eigen::Matrix2d rotation = TangentBasis(a).transpose() * u;  // the feature's axes in B(a)
  const double s = -feature.point.dot(a);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();  // M2, columns (o1, o2, b1, b2)
  m.block<2, 2>(0, 2) = rotation;
  m.block<2, 2>(2, 0) = rotation;
  m.block<2, 2>(2, 2) = s * rotation;
  Eigen::Matrix4d covariance = m * FiniteOrZero(feature.covariance) * m.transpose();
  covariance.diagonal() += Eigen::Vector4d(floors.line_direction_sigma_rad, floors.line_direction_sigma_rad,
                                           floors.line_offset_sigma_m, floors.line_offset_sigma_m)
                               .cwiseAbs2();
  return LineMeasurement{*line, covariance.inverse()};
}

}  // namespace flat2d::localization::landmarks
