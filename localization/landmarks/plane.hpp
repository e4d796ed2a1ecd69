// A 3D plane landmark and its representations (thesis A.3): the general coefficients
// (a, b, c, d) of ax + by + cz + d = 0 (A.19), the Hessian normal form with unit normal n
// and offset p = d / |(a, b, c)| (A.20-A.24), and the minimal triplet (theta, phi, p) of
// the normal's azimuth and polar angle and the offset (A.25-A.26).
//
// Sign convention: a plane is the set n.x + d = 0 with |n| = 1, so d is the thesis' p
// (A.24 reads n.x = -p) and the point of the plane nearest the origin is -d n. (n, d) and
// (-n, -d) are the same geometric plane; the representation keeps the orientation it was
// given, and the factors (landmark_factors.hpp) do not depend on it.
//
// What the solver uses: the Hessian form, perturbed on its manifold S^2 x R by a
// 3-vector delta = (delta_1, delta_2, delta_d):
//   n <- cos|v| n + sin|v| v / |v|,  v = B(n) (delta_1, delta_2),   d <- d + delta_d   (P1)
// with B(n) = TangentBasis(n) (so3.hpp): the normal moves along the great circle towards v
// and the update is defined for every normal. The triplet (theta, phi, p) is not used as
// solver state because theta is undefined when n is along +-z (phi = 0 or pi): exactly the
// ground and ceilings, the most common planes of a LiDAR map, where a change of theta does
// not move the plane and the normal equations become singular. The triplet is kept for
// input/output, with the documented convention theta = 0 at the pole.
#pragma once

#include <optional>

#include <Eigen/Geometry>

namespace flat2d::localization::landmarks {

// Hessian normal form: normal.dot(x) + distance = 0, |normal| = 1.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double distance = 0.0;
};

// The minimal triplet of A.25-A.26.
struct PlaneAngles {
  double azimuth = 0.0;    // theta = atan2(n_y, n_x) in (-pi, pi]; 0 when n is along +-z
  double elevation = 0.0;  // phi = acos(n_z) in [0, pi], the angle from +z (A.26, r = 1)
  double distance = 0.0;   // p = d
};

// A.20-A.24. nullopt when (a, b, c) is zero (below 1e-12 in norm) or a coefficient is not
// finite: such coefficients describe no plane.
std::optional<Plane> PlaneFromCoefficients(const Eigen::Vector4d& abcd);

// (n, d): the coefficients with |(a, b, c)| = 1.
Eigen::Vector4d Coefficients(const Plane& plane);

// A.25-A.26, with phi taken as atan2(|(n_x, n_y)|, n_z), which equals acos(n_z) for a unit
// normal but keeps full precision near the poles. Normals within 1e-12 of +-z count as the
// pole and get theta = 0.
PlaneAngles ToAngles(const Plane& plane);

// The inverse of ToAngles: n = (sin phi cos theta, sin phi sin theta, cos phi), d = p.
Plane FromAngles(const PlaneAngles& angles);

// The plane in frame a, given the plane in frame b and a_T_b:
//   n_a = R n_b,  d_a = d_b - n_a . t.
Plane Transformed(const Eigen::Isometry3d& a_T_b, const Plane& plane_b);

// P1: the plane moved by a local perturbation on its manifold. Retract(plane, 0) = plane.
Plane Retract(const Plane& plane, const Eigen::Vector3d& delta);

// The inverse of P1: the delta with Retract(from, delta) = to, for normals less than pi
// apart (antipodal normals have no unique great circle; the result then has zero angle).
Eigen::Vector3d Local(const Plane& from, const Plane& to);

}  // namespace flat2d::localization::landmarks
