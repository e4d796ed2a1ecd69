// The small pieces of SO(3) that the landmark representations and factors share: the
// skew-symmetric matrix [v]x, the exponential and logarithm maps (Rodrigues' formula, the
// "locally non singular parameterization" of thesis A.1/A.2), and an orthonormal basis of
// the plane orthogonal to a unit vector, the tangent space in which planes and lines are
// perturbed and compared (thesis A.2-A.3).
#pragma once

#include <cmath>

#include <Eigen/Geometry>

namespace flat2d::localization::landmarks {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// [v]x, so that Hat(v) * w = v x w.
inline Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// exp([w]x): the rotation of angle |w| about w.
inline Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  // Below this the first-order form is exact to rounding and w / angle would lose digits.
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + Hat(w);
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

// The inverse of ExpSo3 for rotations of angle below pi.
inline Eigen::Vector3d LogSo3(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd angle_axis(rotation);
  return angle_axis.angle() * angle_axis.axis();
}

// Columns e1, e2 with (e1, e2, unit) a right-handed orthonormal frame. A fixed function of
// `unit`, so an error or a retraction expressed in it is reproducible; its continuity does
// not matter because it is only ever used as a chart at one linearization point.
inline Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& unit) {
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = unit.unitOrthogonal();
  basis.col(1) = unit.cross(basis.col(0));
  return basis;
}

}  // namespace flat2d::localization::landmarks
