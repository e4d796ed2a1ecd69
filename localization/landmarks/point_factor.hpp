// The point landmark factor of landmark SLAM (thesis 8.2: "a landmark can be either a 3D
// line, a 3D plane or a 3D key-point"), for the comparison with NARF key-points (thesis
// Fig. 8.5-8.6). A key-point p_m measured in the sensor frame observes a point landmark p
// kept in its anchor frame; with anchor_T_sensor = (R, t) the prediction is
// p_s = R^T (p - t) and the error, in metres in the sensor frame,
//   e = p_m - R^T (p - t)                                                          (F4)
// Under the right perturbation F1 (landmark_factors.hpp), R <- R exp([dtheta]x),
// t <- t + R dt, the prediction moves to exp(-[dtheta]x) (p_s - dt) ~ p_s - dt + [p_s]x dtheta,
// so
//   de/d(dt) = I,   de/d(dtheta) = -[p_s]x,   de/dp = -R^T                           (F4')
// with the point retracted additively, p <- p + delta. F4 is exact in dt and p; only the
// rotation is linearized. As for F2 and F3 (graph_factors.hpp, O2), the anchor on the left
// leaves the sensor Jacobian unchanged and the vehicle's is J_sensor A.
//
// A key-point carries no covariance of its own (NARF gives a position and an interest
// value), so its information is isotropic from a stated sigma.
#pragma once

#include <Eigen/Geometry>

#include "localization/landmarks/graph_factors.hpp"

namespace flat2d::localization::landmarks {

struct PointFactorLinearization {
  Eigen::Vector3d error = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> jacobian_pose = Eigen::Matrix<double, 3, 6>::Zero();  // (dt, dtheta)
  Eigen::Matrix3d jacobian_point = Eigen::Matrix3d::Zero();                          // additive delta
};

// F4 for a point in the frame anchor_T_sensor is relative to.
Eigen::Vector3d PointError(const Eigen::Isometry3d& anchor_T_sensor, const Eigen::Vector3d& anchor_point,
                           const Eigen::Vector3d& measured_in_sensor);

// F4 and F4' with respect to the sensor pose.
PointFactorLinearization LinearizePoint(const Eigen::Isometry3d& anchor_T_sensor, const Eigen::Vector3d& anchor_point,
                                        const Eigen::Vector3d& measured_in_sensor);

// F4 with the pose Jacobian taken with respect to the vehicle pose (O2).
PointFactorLinearization LinearizePointObservation(const ObservationGeometry& geometry,
                                                   const Eigen::Vector3d& anchor_point,
                                                   const Eigen::Vector3d& measured_in_sensor);

// sigma^-2 I: the information of a key-point measured with `sigma_m` per axis.
Eigen::Matrix3d PointInformation(double sigma_m);

}  // namespace flat2d::localization::landmarks
