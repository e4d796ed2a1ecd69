#include "localization/landmarks/point_factor.hpp"

namespace flat2d::localization::landmarks {

Eigen::Vector3d PointError(const Eigen::Isometry3d& anchor_T_sensor, const Eigen::Vector3d& anchor_point,
                           const Eigen::Vector3d& measured_in_sensor) {
  return measured_in_sensor - anchor_T_sensor.inverse() * anchor_point;
}

PointFactorLinearization LinearizePoint(const Eigen::Isometry3d& anchor_T_sensor, const Eigen::Vector3d& anchor_point,
                                        const Eigen::Vector3d& measured_in_sensor) {
  const Eigen::Matrix3d rt = anchor_T_sensor.linear().transpose();
  const Eigen::Vector3d predicted = rt * (anchor_point - anchor_T_sensor.translation());
  PointFactorLinearization result;
  result.error = measured_in_sensor - predicted;
  result.jacobian_pose.block<3, 3>(0, 0).setIdentity();
  result.jacobian_pose.block<3, 3>(0, 3) = -Hat(predicted);
  result.jacobian_point = -rt;
  return result;
}

PointFactorLinearization LinearizePointObservation(const ObservationGeometry& geometry,
                                                   const Eigen::Vector3d& anchor_point,
                                                   const Eigen::Vector3d& measured_in_sensor) {
  PointFactorLinearization result = LinearizePoint(geometry.AnchorTSensor(), anchor_point, measured_in_sensor);
  result.jacobian_pose = result.jacobian_pose * geometry.sensor_of_vehicle;
  return result;
}

Eigen::Matrix3d PointInformation(double sigma_m) { return Eigen::Matrix3d::Identity() / (sigma_m * sigma_m); }

}  // namespace flat2d::localization::landmarks
