// The factor math of SE(3) pose graphs (thesis 3.4.2, eqs. 3.25 and 3.66-3.70, Alg. 6):
// the retraction, the between error and its Jacobians.
//
// Retraction ("boxplus", eq. 3.25), delta = (dt, w), translation first:
//   X [+] delta = (R Exp(w), t + dt)                                            (G1)
// a right perturbation of the rotation and a world-frame increment of the position, so the
// inverse of the information matrix at a solution is the covariance of the position in
// world axes and of the rotation in the node's own axes.
//
// Between error (g2o's EDGE_SE3:QUAT), E = inv(Z) inv(X_i) X_j, R_A = R_i^T R_j:
//   e = [t_E; q_E.vec],  q_E the unit quaternion of R_E with q_E.w >= 0           (G2)
// This is g2o's own error (toVectorMQT), with no factor 2 on the quaternion: for a small
// rotation angle a, |q.vec| = sin(a / 2) ~ a / 2, so g2o's chi2 weighs a rotation error by a
// quarter of what the same information gives it on the rotation vector (GTSAM).
// With d = t_j - t_i, Q = (q.w I + [q.vec]x) / 2 and [.]x the skew matrix:
//   de_t/ddt_i = -Rz^T R_i^T,  de_t/dw_i = Rz^T [R_i^T d]x,  de_t/ddt_j = Rz^T R_i^T,
//   de_q/dw_i = -Q R_A^T,       de_q/dw_j = Q,  all others 0.                     (G3)
//
// The same error carries SE-Sync's objective exactly (Rosen et al., IJRR 2019, eq. 12):
//   |t_E| = |t_j - t_i - R_i t_z|   and   |R_j - R_i R_z|_F^2 = 4 (1 - cos a) = 8 |q_E.vec|^2,
// so tau |e_t|^2 + 8 kappa |e_q|^2 is SE-Sync's edge term (se3_costs.hpp, ToSeSyncProblem).
// Written as the 9 entries of R_j - R_i R_z instead, the residual leaves the rotations'
// tangent space, Gauss-Newton's J^T J misses its curvature and the iteration converges only
// linearly (torus: 31 iterations against 3, stopping above the optimum).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

// [v]x, so that Hat(v) * u = v x u.
Eigen::Matrix3d Hat(const Eigen::Vector3d& v);
// exp([w]x): the rotation of angle |w| about w (Rodrigues).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& w);

// G1. The rotation is re-orthonormalized, so retractions do not accumulate rounding.
Eigen::Isometry3d Retract(const Eigen::Isometry3d& pose, const Vector6d& delta);

// G2.
Vector6d Se3BetweenError(const Eigen::Isometry3d& pose_i, const Eigen::Isometry3d& pose_j,
                         const Eigen::Isometry3d& measurement);

// G2 and its Jacobians G3 with respect to G1 perturbations of the two poses.
struct Se3BetweenLinearization {
  Vector6d error;
  Matrix6d jacobian_i;
  Matrix6d jacobian_j;
};
Se3BetweenLinearization LinearizeSe3Between(const Eigen::Isometry3d& pose_i,
                                            const Eigen::Isometry3d& pose_j,
                                            const Eigen::Isometry3d& measurement);

}  // namespace flat2d::localization::graph
