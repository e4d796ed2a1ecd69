#include "localization/landmarks/landmark_factors.hpp"

namespace flat2d::localization::landmarks {

namespace {

using Matrix46d = Eigen::Matrix<double, 4, 6>;
using Matrix64d = Eigen::Matrix<double, 6, 4>;

// s of F2: flips the prediction onto the measurement's orientation.
double OrientationSign(const Plane& predicted, const Plane& measured) {
  return predicted.normal.dot(measured.normal) < 0.0 ? -1.0 : 1.0;
}

// F2 for a prediction already in the sensor frame.
Eigen::Vector3d PlaneErrorOf(const Plane& predicted, const Plane& measured, double sign) {
  Eigen::Vector3d error;
  error << sign * TangentBasis(measured.normal).transpose() * predicted.normal,
      sign * predicted.distance - measured.distance;
  return error;
}

// F3 written as e = M (a_p; b_p).
Matrix46d LineErrorMatrix(const PluckerLine& measured) {
  const Eigen::Vector3d a_m = Direction(measured);
  const Eigen::Vector3d q_m = ClosestPointToOrigin(measured);
  const Eigen::Matrix<double, 2, 3> bt = TangentBasis(a_m).transpose();
  Matrix46d m = Matrix46d::Zero();
  m.block<2, 3>(0, 0) = bt;
  // a_m x (a_p x q_m - b_p) = [a_m]x (-[q_m]x a_p - b_p).
  m.block<2, 3>(2, 0) = -bt * Hat(a_m) * Hat(q_m);
  m.block<2, 3>(2, 3) = -bt * Hat(a_m);
  return m;
}

Vector6d Stacked(const PluckerLine& line) {
  Vector6d coordinates;
  coordinates << line.a, line.b;
  return coordinates;
}

// d(a_p, b_p) / d(dt, dtheta) under F1. With R <- R (I + [dtheta]x), t <- t + R dt:
//   a_p <- a_p + [a_p]x dtheta,   b_p <- b_p + [b_p]x dtheta - [a_p]x dt.
Matrix6d PredictedLineByPose(const PluckerLine& predicted) {
  Matrix6d j = Matrix6d::Zero();
  j.block<3, 3>(0, 3) = Hat(predicted.a);
  j.block<3, 3>(3, 0) = -Hat(predicted.a);
  j.block<3, 3>(3, 3) = Hat(predicted.b);
  return j;
}

// d(a_p, b_p) / d(theta_1..3, theta) under A.17-A.18. With U <- U (I + [theta]x) and
// rho = w21 / w11 <- rho + (1 + rho^2) theta, the world line (u1, rho u2) moves by
//   da_w = (0, -u3, u2, 0),   db_w = (rho u3, 0, -rho u1, (1 + rho^2) u2),
// and the prediction a_p = R^T a_w, b_p = R^T (b_w + t x a_w) follows.
Matrix64d PredictedLineByLandmark(const Eigen::Isometry3d& world_T_sensor, const OrthonormalLine& line) {
  const double rho = line.W(1, 0) / line.W(0, 0);
  const Eigen::Vector3d u1 = line.U.col(0);
  const Eigen::Vector3d u2 = line.U.col(1);
  const Eigen::Vector3d u3 = line.U.col(2);
  Eigen::Matrix<double, 3, 4> da = Eigen::Matrix<double, 3, 4>::Zero();
  da.col(1) = -u3;
  da.col(2) = u2;
  Eigen::Matrix<double, 3, 4> db;
  db << rho * u3, Eigen::Vector3d::Zero(), -rho * u1, (1.0 + rho * rho) * u2;
  const Eigen::Matrix3d rt = world_T_sensor.linear().transpose();
  Matrix64d j;
  j.topRows<3>() = rt * da;
  j.bottomRows<3>() = rt * (db + Hat(world_T_sensor.translation()) * da);
  return j;
}

}  // namespace

Eigen::Isometry3d RetractPose(const Eigen::Isometry3d& world_T_sensor, const Vector6d& delta) {
  Eigen::Isometry3d increment = Eigen::Isometry3d::Identity();
  increment.linear() = ExpSo3(delta.tail<3>());
  increment.translation() = delta.head<3>();
  return world_T_sensor * increment;
}

Eigen::Vector3d PlaneError(const Eigen::Isometry3d& world_T_sensor, const Plane& world_plane,
                           const Plane& measured_in_sensor) {
  const Plane predicted = Transformed(world_T_sensor.inverse(), world_plane);
  return PlaneErrorOf(predicted, measured_in_sensor, OrientationSign(predicted, measured_in_sensor));
}

PlaneFactorLinearization LinearizePlane(const Eigen::Isometry3d& world_T_sensor, const Plane& world_plane,
                                        const Plane& measured_in_sensor) {
  const Plane predicted = Transformed(world_T_sensor.inverse(), world_plane);
  const double sign = OrientationSign(predicted, measured_in_sensor);
  const Eigen::Matrix<double, 2, 3> bt = sign * TangentBasis(measured_in_sensor.normal).transpose();
  const Eigen::Matrix<double, 3, 2> b_world = TangentBasis(world_plane.normal);
  const Eigen::Matrix3d rt = world_T_sensor.linear().transpose();
  PlaneFactorLinearization result;
  result.error = PlaneErrorOf(predicted, measured_in_sensor, sign);
  // Under F1, n_p <- n_p + [n_p]x dtheta and d_p <- d_p + n_p . dt.
  result.jacobian_pose.block<2, 3>(0, 3) = bt * Hat(predicted.normal);
  result.jacobian_pose.block<1, 3>(2, 0) = sign * predicted.normal.transpose();
  // Under P1, n_w <- n_w + B(n_w) delta_12 and d_w <- d_w + delta_d, so
  // n_p moves by R^T B(n_w) delta_12 and d_p = d_w + n_w . t by t^T B(n_w) delta_12 + delta_d.
  result.jacobian_plane.block<2, 2>(0, 0) = bt * rt * b_world;
  result.jacobian_plane.block<1, 2>(2, 0) = sign * world_T_sensor.translation().transpose() * b_world;
  result.jacobian_plane(2, 2) = sign;
  return result;
}

std::optional<Eigen::Vector4d> LineError(const Eigen::Isometry3d& world_T_sensor,
                                         const OrthonormalLine& world_line,
                                         const PluckerLine& measured_in_sensor) {
  const std::optional<PluckerLine> world = ToPlucker(world_line);
  if (!world) return std::nullopt;
  const PluckerLine predicted = Transformed(world_T_sensor.inverse(), *world);
  return Eigen::Vector4d(LineErrorMatrix(measured_in_sensor) * Stacked(predicted));
}

std::optional<LineFactorLinearization> LinearizeLine(const Eigen::Isometry3d& world_T_sensor,
                                                     const OrthonormalLine& world_line,
                                                     const PluckerLine& measured_in_sensor) {
  const std::optional<PluckerLine> world = ToPlucker(world_line);
  if (!world) return std::nullopt;
  const PluckerLine predicted = Transformed(world_T_sensor.inverse(), *world);
  const Matrix46d m = LineErrorMatrix(measured_in_sensor);
  LineFactorLinearization result;
  result.error = m * Stacked(predicted);
  result.jacobian_pose = m * PredictedLineByPose(predicted);
  result.jacobian_line = m * PredictedLineByLandmark(world_T_sensor, world_line);
  return result;
}

}  // namespace flat2d::localization::landmarks
