// The measurement errors of landmark SLAM with plane and line landmarks (thesis 8.2: a
// pose observes a landmark it was associated with, and a factor joins the pose node to
// the landmark node), with analytic Jacobians for a Gauss-Newton solver.
//
// Pose: world_T_sensor = (R, t), perturbed on the RIGHT, in the sensor frame, by
// delta = (dt, dtheta):
//   world_T_sensor [+] delta = world_T_sensor * (exp([dtheta]x), dt)           (F1)
// i.e. R <- R exp([dtheta]x), t <- t + R dt. The landmarks are perturbed by their own
// retractions: Retract(Plane, 3-vector) (plane.hpp, P1) and Retract(OrthonormalLine,
// 4-vector) (line.hpp, A.17-A.18). Jacobians are those of the error at delta = 0.
//
// Plane factor, 3D error in the tangent space of the measured plane (n_m, d_m), with
// (n_p, d_p) the world plane predicted in the sensor frame (n_p = R^T n_w,
// d_p = d_w + n_w . t) and s = sign(n_p . n_m):
//   e = (B(n_m)^T s n_p, s d_p - d_m)                                          (F2)
// B(n_m) = TangentBasis(n_m) (so3.hpp). The first two entries are the normal difference
// s n_p - n_m projected on the plane's tangent space (B^T n_m = 0), sin of the angle
// between the normals; the last is the offset difference in metres. Three entries for
// three degrees of freedom, so a measurement covariance in (tangent, offset) is a full-rank
// 3x3 matrix, where the 4D (n, d) difference would carry a direction with no information.
// The sign s makes the error blind to the orientation of either normal, since (n, d) and
// (-n, -d) are the same plane; the flip happens only 90 degrees away from agreement.
//
// Line factor, 4D error in the frame of the measured line (unit direction a_m, point q_m
// nearest the sensor), with (a_p, b_p) the world line predicted in the sensor frame
// (a_p = R^T a_w, b_p = R^T (b_w + t x a_w)):
//   e = (B(a_m)^T a_p, B(a_m)^T (a_m x (a_p x q_m - b_p)))                     (F3)
// The first pair is the direction difference, sin of the angle between the directions; the
// second, a_p x q_m - b_p = a_p x (q_m - P_p), is the perpendicular offset from q_m to the
// predicted line turned by 90 degrees about it, turned back by a_m x: at agreeing
// directions it is exactly the offset, in metres, expressed in B(a_m). Four entries for a
// line's four degrees of freedom. Both pairs are unchanged when (a, b) flip sign, so the
// line's orientation does not matter either. F3 is linear in (a_p, b_p), which keeps its
// Jacobians short.
//
// "World" is whatever frame holds the landmark. For a line kept in an anchor frame
// (line.hpp: the orthonormal chart is singular for lines through its origin), pass
// anchor_T_sensor = anchor_T_world * world_T_sensor: under F1 a fixed factor on the left
// leaves the pose Jacobian unchanged, so it applies to world_T_sensor as it stands.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "localization/landmarks/line.hpp"
#include "localization/landmarks/plane.hpp"
#include "localization/landmarks/so3.hpp"

namespace flat2d::localization::landmarks {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// F1.
Eigen::Isometry3d RetractPose(const Eigen::Isometry3d& world_T_sensor, const Vector6d& delta);

struct PlaneFactorLinearization {
  Eigen::Vector3d error = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> jacobian_pose = Eigen::Matrix<double, 3, 6>::Zero();  // (dt, dtheta)
  Eigen::Matrix3d jacobian_plane = Eigen::Matrix3d::Zero();                          // P1's delta
};

struct LineFactorLinearization {
  Eigen::Vector4d error = Eigen::Vector4d::Zero();
  Eigen::Matrix<double, 4, 6> jacobian_pose = Eigen::Matrix<double, 4, 6>::Zero();  // (dt, dtheta)
  Eigen::Matrix4d jacobian_line = Eigen::Matrix4d::Zero();                           // A.17-A.18's delta
};

// F2 for a plane measured in the sensor frame.
Eigen::Vector3d PlaneError(const Eigen::Isometry3d& world_T_sensor, const Plane& world_plane,
                           const Plane& measured_in_sensor);

// F2 and its Jacobians.
PlaneFactorLinearization LinearizePlane(const Eigen::Isometry3d& world_T_sensor, const Plane& world_plane,
                                        const Plane& measured_in_sensor);

// F3 for a line measured in the sensor frame (|a| = 1, as the line.hpp constructors give).
// nullopt when the landmark lies at infinity (ToPlucker fails).
std::optional<Eigen::Vector4d> LineError(const Eigen::Isometry3d& world_T_sensor,
                                         const OrthonormalLine& world_line,
                                         const PluckerLine& measured_in_sensor);

// F3 and its Jacobians; nullopt as LineError.
std::optional<LineFactorLinearization> LinearizeLine(const Eigen::Isometry3d& world_T_sensor,
                                                     const OrthonormalLine& world_line,
                                                     const PluckerLine& measured_in_sensor);

}  // namespace flat2d::localization::landmarks
