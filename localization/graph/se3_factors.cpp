#include "localization/graph/se3_factors.hpp"

#include <cmath>

namespace flat2d::localization::graph {
namespace {

// The unit quaternion of a rotation with w >= 0 (g2o's normalization: q and -q are the same
// rotation, and w >= 0 picks the one whose vector part is small for small angles).
Eigen::Quaterniond PositiveQuaternion(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q;
}

}  // namespace

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return s;
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  // Below this the first-order form is exact to rounding and w / angle would lose digits.
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + Hat(w);
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Isometry3d Retract(const Eigen::Isometry3d& pose, const Vector6d& delta) {
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d rotation = pose.linear() * ExpSo3(delta.tail<3>());
  moved.linear() = Eigen::Quaterniond(rotation).normalized().toRotationMatrix();
  moved.translation() = pose.translation() + delta.head<3>();
  return moved;
}

Vector6d Se3BetweenError(const Eigen::Isometry3d& pose_i, const Eigen::Isometry3d& pose_j,
                         const Eigen::Isometry3d& measurement) {
  const Eigen::Isometry3d e = measurement.inverse() * pose_i.inverse() * pose_j;
  Vector6d error;
  error << e.translation(), PositiveQuaternion(e.linear()).vec();
  return error;
}

Se3BetweenLinearization LinearizeSe3Between(const Eigen::Isometry3d& pose_i,
                                            const Eigen::Isometry3d& pose_j,
                                            const Eigen::Isometry3d& measurement) {
  const Eigen::Matrix3d rz_t = measurement.linear().transpose();
  const Eigen::Matrix3d ri_t = pose_i.linear().transpose();
  const Eigen::Matrix3d relative = ri_t * pose_j.linear();  // R_A
  const Eigen::Vector3d d_in_i = ri_t * (pose_j.translation() - pose_i.translation());
  const Eigen::Quaterniond q = PositiveQuaternion(rz_t * relative);
  const Eigen::Matrix3d dq = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + Hat(q.vec()));

  Se3BetweenLinearization lin;
  lin.error << rz_t * (d_in_i - measurement.translation()), q.vec();
  lin.jacobian_i.setZero();
  lin.jacobian_j.setZero();
  lin.jacobian_i.topLeftCorner<3, 3>() = -rz_t * ri_t;  // G3
  lin.jacobian_i.topRightCorner<3, 3>() = rz_t * Hat(d_in_i);
  lin.jacobian_i.bottomRightCorner<3, 3>() = -dq * relative.transpose();
  lin.jacobian_j.topLeftCorner<3, 3>() = rz_t * ri_t;
  lin.jacobian_j.bottomRightCorner<3, 3>() = dq;
  return lin;
}

}  // namespace flat2d::localization::graph
