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

// Sums of the pairs' terms, from which H and b follow in closed form. Each error block
// has the Jacobian J = [I, A] (point) or [0, A] (normal) with A = -2 [x]x (Eq. 5.17) and
// the information Omega = w (I + g n n^T) (surfel_cloud.hpp). Then
//   J^T Omega J = w J^T J + w g v v^T,   J^T Omega e = w J^T e + w g (n.e) v,   v = J^T n,
// and the identity parts only need moments of x: sum w, sum w x, sum w x x^T.
struct Moments {
  double weight = 0.0;                          // sum w          (point blocks)
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // sum w x        (point blocks)
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(); // sum w x x^T    (point and normal blocks)
  double x_squared = 0.0;                       // sum w |x|^2    (point and normal blocks)
  Eigen::Vector3d e = Eigen::Vector3d::Zero();  // sum w e        (point blocks)
  Eigen::Vector3d x_cross_e = Eigen::Vector3d::Zero();  // sum w x x e (both)
  Matrix6d rank_one = Matrix6d::Zero();         // sum w g v v^T
  Vector6d rank_one_b = Vector6d::Zero();       // sum w g (n.e) v
};

// One block: `x` the moved source point (or normal), `e` its error, `n` the target normal.
void AddBlock(const Eigen::Vector3d& x, const Eigen::Vector3d& e, const Eigen::Vector3d& n, double w, double g,
              bool point_block, Moments& m) {
  m.xx.noalias() += w * x * x.transpose();
  m.x_squared += w * x.squaredNorm();
  m.x_cross_e += w * x.cross(e);
  if (point_block) {
    m.weight += w;
    m.x += w * x;
    m.e += w * e;
  }
  if (g <= 0.0) return;
  Vector6d v;
  v.head<3>() = point_block ? n : Eigen::Vector3d::Zero();
  v.tail<3>() = 2.0 * x.cross(n);  // A^T n = 2 [x]x n
  const double wg = w * g;
  for (int col = 0; col < 6; ++col) {  // the upper triangle; Assemble() mirrors it
    const double scaled = wg * v[col];
    for (int row = 0; row <= col; ++row) m.rank_one(row, col) += scaled * v[row];
  }
  m.rank_one_b += (w * g * n.dot(e)) * v;
}

// H = sum J^T J + rank-one terms: [[sum w I, -2 [sum w x]x], [.., 4 (sum w |x|^2 I - sum w x x^T)]].
void Assemble(const Moments& m, LinearSystem& system) {
  system.H.topLeftCorner<3, 3>() = m.weight * Eigen::Matrix3d::Identity();
  system.H.topRightCorner<3, 3>() = -2.0 * Skew(m.x);
  system.H.bottomLeftCorner<3, 3>() = system.H.topRightCorner<3, 3>().transpose();
  system.H.bottomRightCorner<3, 3>() = 4.0 * (m.x_squared * Eigen::Matrix3d::Identity() - m.xx);
  system.H += m.rank_one.selfadjointView<Eigen::Upper>();
  system.b.head<3>() = m.e;
  system.b.tail<3>() = 2.0 * m.x_cross_e;  // A^T e = 2 x x e
  system.b += m.rank_one_b;
}

}  // namespace

LinearSystem BuildLinearSystem(const maps::range3d::SurfelCloud& target, const maps::range3d::SurfelCloud& source,
                               const std::vector<Correspondence>& pairs, const Eigen::Isometry3f& target_T_source,
                               const NicpOptions& options) {
  LinearSystem system;
  Moments moments;
  const bool with_normals = options.metric == ErrorMetric::kNicp;
  const Eigen::Matrix3f rotation = target_T_source.linear();
  for (const Correspondence& pair : pairs) {
    const Eigen::Vector3d x = (target_T_source * source.points[pair.source]).cast<double>();
    const Eigen::Vector3d m = (rotation * source.normals[pair.source]).cast<double>();
    const Eigen::Vector3d n = target.normals[pair.target].cast<double>();
    const double g = target.disc_gain[pair.target];
    const Eigen::Vector3d point_error = x - target.points[pair.target].cast<double>();  // Eq. 5.11
    const Eigen::Vector3d normal_error = m - n;

    const double along = n.dot(point_error);
    double chi2 = point_error.squaredNorm() + g * along * along;
    if (with_normals) {
      const double normal_along = n.dot(normal_error);
      chi2 += options.normal_weight * (normal_error.squaredNorm() + g * normal_along * normal_along);
    }
    const bool inlier = chi2 < options.chi2_bound;
    const double gamma = inlier ? 1.0 : options.chi2_bound / chi2;  // Eq. 4.11
    system.inliers += inlier ? 1 : 0;
    system.chi2 += gamma * chi2;
    AddBlock(x, point_error, n, gamma, g, true, moments);
    if (with_normals) AddBlock(m, normal_error, n, gamma * options.normal_weight, g, false, moments);
  }
  Assemble(moments, system);
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
