#include "localization/landmarks/graph_factors.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::localization::landmarks {

Vector6d OdometryError(const Eigen::Isometry3d& world_T_from, const Eigen::Isometry3d& world_T_to,
                       const Eigen::Isometry3d& from_T_to_measured) {
  const Eigen::Isometry3d e = from_T_to_measured.inverse() * world_T_from.inverse() * world_T_to;
  Vector6d error;
  error << e.translation(), LogSo3(e.linear());
  return error;
}

OdometryLinearization LinearizeOdometry(const Eigen::Isometry3d& world_T_from, const Eigen::Isometry3d& world_T_to,
                                        const Eigen::Isometry3d& from_T_to_measured) {
  const Eigen::Isometry3d e = from_T_to_measured.inverse() * world_T_from.inverse() * world_T_to;
  const Eigen::Matrix3d rz_t = from_T_to_measured.linear().transpose();
  const Eigen::Vector3d& tz = from_T_to_measured.translation();
  OdometryLinearization result;
  result.error << e.translation(), LogSo3(e.linear());
  // X_j <- X_j (exp(dtheta), dt) gives E <- E (exp(dtheta), dt): t_E + R_E dt, R_E exp(dtheta).
  result.jacobian_to.block<3, 3>(0, 0) = e.linear();
  result.jacobian_to.block<3, 3>(3, 3).setIdentity();
  // X_i <- X_i (exp(dtheta), dt) gives E <- (I - [a]x, b) E with a = R_Z^T dtheta and
  // b = R_Z^T ([t_Z]x dtheta - dt): Z^-1 conjugates the inverse step into E's frame.
  result.jacobian_from.block<3, 3>(0, 0) = -rz_t;
  result.jacobian_from.block<3, 3>(0, 3) = Hat(e.translation()) * rz_t + rz_t * Hat(tz);
  result.jacobian_from.block<3, 3>(3, 3) = -e.linear().transpose() * rz_t;
  return result;
}

Matrix6d OdometryInformation(const Eigen::Isometry3d& from_T_to_measured, const OdometryNoise& noise) {
  const double distance = from_T_to_measured.translation().head<2>().norm();
  const double turn = Eigen::AngleAxisd(from_T_to_measured.linear()).angle();
  const double sigma_xy = std::max(noise.translation_sigma_per_m * distance, noise.translation_sigma_min_m);
  const double sigma_yaw = std::max(noise.heading_sigma_per_m * distance + noise.heading_sigma_per_rad * turn,
                                    noise.heading_sigma_min_rad);
  Vector6d sigma;
  sigma << sigma_xy, sigma_xy, noise.z_sigma_m, noise.roll_pitch_sigma_rad, noise.roll_pitch_sigma_rad, sigma_yaw;
  return sigma.cwiseAbs2().cwiseInverse().asDiagonal();
}

Matrix6d SensorPerturbationOfVehicle(const Eigen::Isometry3d& vehicle_T_sensor) {
  const Eigen::Matrix3d rs_t = vehicle_T_sensor.linear().transpose();
  Matrix6d a = Matrix6d::Zero();
  a.block<3, 3>(0, 0) = rs_t;
  a.block<3, 3>(0, 3) = -rs_t * Hat(vehicle_T_sensor.translation());
  a.block<3, 3>(3, 3) = rs_t;
  return a;
}

PlaneFactorLinearization LinearizePlaneObservation(const ObservationGeometry& geometry, const Plane& anchor_plane,
                                                   const Plane& measured_in_sensor) {
  PlaneFactorLinearization result = LinearizePlane(geometry.AnchorTSensor(), anchor_plane, measured_in_sensor);
  result.jacobian_pose = result.jacobian_pose * geometry.sensor_of_vehicle;
  return result;
}

std::optional<LineFactorLinearization> LinearizeLineObservation(const ObservationGeometry& geometry,
                                                                const OrthonormalLine& anchor_line,
                                                                const PluckerLine& measured_in_sensor) {
  std::optional<LineFactorLinearization> result =
      LinearizeLine(geometry.AnchorTSensor(), anchor_line, measured_in_sensor);
  if (result) result->jacobian_pose = result->jacobian_pose * geometry.sensor_of_vehicle;
  return result;
}

}  // namespace flat2d::localization::landmarks
