// SE(2), the rigid motions of the plane: the pose type of the odometry module, its
// exponential map for arcs and interpolation, and the Jacobians of covariance propagation
// (Sola, Deray, Atchuthan, "A micro Lie theory for state estimation in robotics", 2018,
// appendix C, with the equations written out here as E1-E7).
//
// An Se2 a_T_b holds the position (x, y) of b's origin in a and b's heading theta in a
// (counter-clockwise, kept in (-pi, pi]); it maps points of b into a: p_a = R(theta) p_b + t.
// Composition is a_T_c = a_T_b * b_T_c. A twist xi = (rho_x, rho_y, phi) is a body-frame
// velocity held for unit time; its motion is the circular arc
//   Exp(xi) = (V(phi) rho, phi),  V(phi) = [S(phi) -C(phi); C(phi) S(phi)],            (E1)
//   S(phi) = sin(phi) / phi,      C(phi) = (1 - cos(phi)) / phi,
//   Log(T)  = (V(theta)^-1 t, theta), V^-1 = [h cot h, h; -h, h cot h], h = theta / 2,   (E2)
// with Taylor series near phi = 0. Geodesic interpolation: a * Exp(s Log(a^-1 b)).      (E3)
//
// Covariance convention: a pose's covariance is that of its components (x, y, theta),
// x and y along the axes of the parent frame, theta an angle difference; small errors add
// to the components (as in ROS nav_msgs/Odometry). For c = a * b, with u = R(a.theta) b.t:
//   J_a = [1 0 -u.y; 0 1 u.x; 0 0 1],  J_b = [R(a.theta) 0; 0 1],                     (E4)
//   cov_c = J_a cov_a J_a^T + J_b cov_b J_b^T   for independent a and b.                (E5)
// For i = a^-1:  J = [-R^T (i.y, -i.x)^T; 0 0 -1]  (rows x, y, theta).                  (E6)
// A unicycle arc of length d and heading change phi is Exp((d, 0, phi)); the Jacobian of
// its components with respect to (d, phi) is [S d*S'; C d*C'; 0 1].                     (E7)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flat2d::localization {

// The angle in (-pi, pi] equal to `angle` modulo 2 pi.
double NormalizeAngle(double angle);

class Se2 {
 public:
  Se2() = default;  // identity
  Se2(double x, double y, double theta);
  Se2(const Eigen::Vector2d& translation, double theta);

  static Se2 Exp(const Eigen::Vector3d& xi);  // E1
  Eigen::Vector3d Log() const;                // E2

  Se2 operator*(const Se2& other) const;
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const;
  Se2 Inverse() const;

  double x() const { return translation_.x(); }
  double y() const { return translation_.y(); }
  double theta() const { return theta_; }
  const Eigen::Vector2d& translation() const { return translation_; }
  Eigen::Matrix2d Rotation() const;
  Eigen::Vector3d Vector() const { return {translation_.x(), translation_.y(), theta_}; }

 private:
  Eigen::Vector2d translation_ = Eigen::Vector2d::Zero();
  double theta_ = 0.0;
};

// The planar pose an isometry holds (the grids' and the gridder's type): translation, and
// the heading of its x axis.
Se2 Se2Of(const Eigen::Isometry2d& pose);

// E3: a at s = 0, b at s = 1, constant body twist in between (s may leave [0, 1]).
Se2 Interpolate(const Se2& a, const Se2& b, double s);

// The component difference (x, y, theta) of two poses in one frame, theta wrapped.
Eigen::Vector3d ComponentDifference(const Se2& a, const Se2& b);  // a - b

struct ComposeJacobians {
  Eigen::Matrix3d wrt_a;
  Eigen::Matrix3d wrt_b;
};

// E4 for c = a * b.
ComposeJacobians ComposeJacobian(const Se2& a, const Se2& b);

// E5: covariance of a * b for independent a (cov_a) and b (cov_b, in a's child frame).
Eigen::Matrix3d ComposeCovariance(const Se2& a, const Eigen::Matrix3d& cov_a, const Se2& b,
                                  const Eigen::Matrix3d& cov_b);

// E6: Jacobian of a^-1's components with respect to a's.
Eigen::Matrix3d InverseJacobian(const Se2& a);

// Exp((distance, 0, heading_change)): the arc a unicycle drives (E1).
Se2 Arc(double distance, double heading_change);

// E7: d(x, y, theta of Arc) / d(distance, heading_change).
Eigen::Matrix<double, 3, 2> ArcJacobian(double distance, double heading_change);

}  // namespace flat2d::localization
