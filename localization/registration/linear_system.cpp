#include "localization/registration/linear_system.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::localization::registration {

namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// Adds gamma * J^T Omega J and gamma * J^T Omega e of one 3D block of Eq. 5.17:
// J = [I, -2 [x]x] for the point (with_translation) or [0, -2 [x]x] for the normal.
void AddBlock(const Eigen::Vector3d& moved, const Eigen::Vector3d& error, const Eigen::Matrix3d& omega,
              bool with_translation, double gamma, LinearSystem& system) {
  const Eigen::Matrix3d rotation_jacobian = -2.0 * Skew(moved);
  const Eigen::Matrix3d omega_rotation = gamma * omega * rotation_jacobian;
  const Eigen::Vector3d omega_error = gamma * omega * error;
  system.H.bottomRightCorner<3, 3>() += rotation_jacobian.transpose() * omega_rotation;
  system.b.tail<3>() += rotation_jacobian.transpose() * omega_error;
  if (!with_translation) return;
  system.H.topLeftCorner<3, 3>() += gamma * omega;
  system.H.topRightCorner<3, 3>() += omega_rotation;
  system.H.bottomLeftCorner<3, 3>() += omega_rotation.transpose();
  system.b.head<3>() += omega_error;
}

}  // namespace

LinearSystem BuildLinearSystem(const maps::range3d::SurfelCloud& target, const maps::range3d::SurfelCloud& source,
                               const std::vector<Correspondence>& pairs, const Eigen::Isometry3f& target_T_source,
                               const NicpOptions& options) {
  LinearSystem system;
  const bool with_normals = options.metric == ErrorMetric::kNicp;
  const Eigen::Isometry3d transform = target_T_source.cast<double>();
  for (const Correspondence& pair : pairs) {
    const Eigen::Vector3d moved_point = transform * source.points[pair.source].cast<double>();
    const Eigen::Vector3d moved_normal = transform.linear() * source.normals[pair.source].cast<double>();
    const Eigen::Vector3d point_error = moved_point - target.points[pair.target].cast<double>();
    const Eigen::Vector3d normal_error = moved_normal - target.normals[pair.target].cast<double>();
    const Eigen::Matrix3d omega_point = target.point_information[pair.target].cast<double>();
    const Eigen::Matrix3d omega_normal = options.normal_weight * target.normal_information[pair.target].cast<double>();

    double chi2 = point_error.dot(omega_point * point_error);
    if (with_normals) chi2 += normal_error.dot(omega_normal * normal_error);
    const bool inlier = chi2 < options.chi2_bound;
    const double gamma = inlier ? 1.0 : options.chi2_bound / chi2;  // Eq. 4.11
    system.inliers += inlier ? 1 : 0;
    system.chi2 += gamma * chi2;
    AddBlock(moved_point, point_error, omega_point, true, gamma, system);
    if (with_normals) AddBlock(moved_normal, normal_error, omega_normal, false, gamma, system);
  }
  return system;
}

Eigen::Isometry3d ApplyIncrement(const Vector6d& increment, const Eigen::Isometry3d& target_T_source) {
  Eigen::Vector3d dq = increment.tail<3>();
  const double norm_squared = dq.squaredNorm();
  if (norm_squared > 1.0) dq /= std::sqrt(norm_squared);  // beyond 180 deg: keep a unit quaternion
  const Eigen::Quaterniond rotation(std::sqrt(std::max(0.0, 1.0 - dq.squaredNorm())), dq.x(), dq.y(), dq.z());
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = rotation.toRotationMatrix();
  delta.translation() = increment.head<3>();
  return delta * target_T_source;
}

}  // namespace flat2d::localization::registration
