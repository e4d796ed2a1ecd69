// The factors of the landmark SLAM graph (thesis 8.2) written for its state: pose nodes are
// world_T_vehicle, landmarks are kept in fixed anchor frames. Three kinds, each an error
// with its Jacobians for Gauss-Newton on the manifold (thesis 3.4.2, Eq. 3.66-3.70):
//
// Odometry factor between consecutive pose nodes i and j with the measured motion Z = i_T_j
// from the dead reckoning (thesis 3.4, Eq. 3.55), on SO(3) x R^3 to match RetractPose (F1):
//   E = Z^-1 X_i^-1 X_j,   e = (t_E, Log R_E)                                       (O1)
// t_E and Log R_E are in node j's vehicle frame, so the information can be planar: tight on
// z, roll and pitch, loose on x, y and yaw. Jacobians take J_r^-1(Log R_E) = I, exact at
// e = 0 and off by O(|e|) where odometry errors are a few millidegrees: the fixed point of
// Gauss-Newton moves by O(|e|^2).
//
// Observation factors F2 (plane) and F3 (line) of landmark_factors.hpp between a pose node
// and a landmark kept in its anchor frame: they see anchor_T_sensor =
// anchor_T_world * world_T_vehicle * vehicle_T_sensor. A right perturbation of the vehicle
// pose is a right perturbation of the sensor pose by
//   delta_sensor = A delta_vehicle,  A = [R_S^T, -R_S^T [t_S]x; 0, R_S^T]             (O2)
// with vehicle_T_sensor = (R_S, t_S), and the fixed anchor on the left leaves the sensor
// Jacobian unchanged (landmark_factors.hpp), so J_vehicle = J_sensor A.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "localization/landmarks/landmark_factors.hpp"

namespace flat2d::localization::landmarks {

// The dead reckoning's noise, per factor between two pose nodes. Standard deviations grow
// linearly with the motion between the nodes (a scale or heading bias of the odometry
// grows that way; a random walk would grow with its square root, and is smaller over the
// sub-metre steps between keyframes), and never fall below the floors, so that a node
// reached by standing still is not infinitely certain.
struct OdometryNoise {
  double translation_sigma_per_m = 0.05;   // x, y error per metre travelled (5 %)
  double translation_sigma_min_m = 0.005;  // floor of the x, y sigma
  double heading_sigma_per_m = 0.005;      // yaw error per metre travelled (0.3 deg/m)
  double heading_sigma_per_rad = 0.05;     // yaw error per radian turned (5 %)
  double heading_sigma_min_rad = 0.0005;   // floor of the yaw sigma
  // The CAN odometry is planar: these keep the trajectory on its plane. Loosen them for a
  // drive with ramps, where the lift of a planar pose is wrong by the slope.
  double z_sigma_m = 0.005;            // per factor
  double roll_pitch_sigma_rad = 0.002;  // per factor
};

struct OdometryLinearization {
  Vector6d error = Vector6d::Zero();
  Matrix6d jacobian_from = Matrix6d::Zero();  // (dt, dtheta) of X_i
  Matrix6d jacobian_to = Matrix6d::Zero();    // (dt, dtheta) of X_j
};

// O1.
Vector6d OdometryError(const Eigen::Isometry3d& world_T_from, const Eigen::Isometry3d& world_T_to,
                       const Eigen::Isometry3d& from_T_to_measured);

// O1 and its Jacobians.
OdometryLinearization LinearizeOdometry(const Eigen::Isometry3d& world_T_from, const Eigen::Isometry3d& world_T_to,
                                        const Eigen::Isometry3d& from_T_to_measured);

// The diagonal information of O1 for a measured motion, from the noise model above.
Matrix6d OdometryInformation(const Eigen::Isometry3d& from_T_to_measured, const OdometryNoise& noise);

// A of O2.
Matrix6d SensorPerturbationOfVehicle(const Eigen::Isometry3d& vehicle_T_sensor);

// Where a landmark factor's pose sits: the vehicle node, the fixed extrinsic, the anchor.
struct ObservationGeometry {
  Eigen::Isometry3d world_T_vehicle = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d world_T_anchor = Eigen::Isometry3d::Identity();
  Matrix6d sensor_of_vehicle = Matrix6d::Identity();  // A of O2 for vehicle_T_sensor

  Eigen::Isometry3d AnchorTSensor() const { return world_T_anchor.inverse() * world_T_vehicle * vehicle_T_sensor; }
};

// F2 with the pose Jacobian taken with respect to the vehicle pose (O2).
PlaneFactorLinearization LinearizePlaneObservation(const ObservationGeometry& geometry, const Plane& anchor_plane,
                                                   const Plane& measured_in_sensor);

// F3 likewise; nullopt when the landmark lies at infinity.
std::optional<LineFactorLinearization> LinearizeLineObservation(const ObservationGeometry& geometry,
                                                                const OrthonormalLine& anchor_line,
                                                                const PluckerLine& measured_in_sensor);

}  // namespace flat2d::localization::landmarks
