// From an extracted 3D feature (thesis 8.1.4) to the measurement of a landmark factor
// (thesis 8.2): the plane or line in the sensor frame and its information matrix in the
// factor's error coordinates (F2, F3 of landmark_factors.hpp), Omega = Sigma_e^-1 of the
// least-squares terms (thesis Eq. 3.15, 3.40).
//
// The feature's covariance is in its own coordinates and is carried into the error's by
// the first-order map A of a feature perturbation onto the error, Sigma_e = A Sigma A^T:
//   plane, (tilt a2 towards u2, tilt a3 towards u3, offset o at the centroid c):
//     dn = a2 u2 + a3 u3,  dd = -(a2 u2 + a3 u3) . c - o,  e ~ -(B(n)^T dn, dd)          (M1)
//   line, (offsets o1, o2 along u1, u2 and tilts b1, b2 towards u1, u2 at the point p):
//     da = b1 u1 + b2 u2,  the offset at q (the point nearest the sensor, q = p + s a,
//     s = -p . a) is o + s da,  e ~ -(B(a)^T da, B(a)^T (o + s da))                    (M2)
// The overall sign does not change Sigma_e. A floor (options below) is then added to the
// diagonal: the cluster's scatter knows nothing of a wall that is not quite flat, a pole
// that is not quite straight, or a feature cut short by an occlusion, and a perfect fit of
// 2000 points would otherwise outweigh the whole odometry.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "localization/landmarks/line.hpp"
#include "localization/landmarks/plane.hpp"
#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::localization::landmarks {

// Standard deviations added (in quadrature) to every measurement's own.
struct MeasurementFloors {
  double plane_normal_sigma_rad = 0.01;   // per tangent axis of the normal
  double plane_offset_sigma_m = 0.03;     // of the offset at the sensor
  double line_direction_sigma_rad = 0.02;  // per tangent axis of the direction
  double line_offset_sigma_m = 0.03;      // per axis across the line
};

struct PlaneMeasurement {
  Plane plane;  // in the sensor frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

struct LineMeasurement {
  PluckerLine line;  // in the sensor frame
  Eigen::Matrix4d information = Eigen::Matrix4d::Identity();
};

// The feature as seen from frame a, given it in frame b: every point and axis is moved, the
// covariance (in the feature's own axes) is unchanged.
maps::features3d::PlaneFeature TransformedFeature(const Eigen::Isometry3d& a_T_b,
                                                  const maps::features3d::PlaneFeature& feature);
maps::features3d::LineFeature TransformedFeature(const Eigen::Isometry3d& a_T_b,
                                                 const maps::features3d::LineFeature& feature);

// M1 and the floor. nullopt for a feature with a non-finite value or a normal or major axis
// that is not a unit vector within 1e-3 (no plane). A covariance that is not finite counts
// as zero, so that the floor alone speaks.
std::optional<PlaneMeasurement> PlaneMeasurementOf(const maps::features3d::PlaneFeature& feature,
                                                   const MeasurementFloors& floors);

// M2 and the floor; nullopt likewise for the direction and across axis.
std::optional<LineMeasurement> LineMeasurementOf(const maps::features3d::LineFeature& feature,
                                                 const MeasurementFloors& floors);

}  // namespace flat2d::localization::landmarks
