// A 3D line landmark and its representations (thesis A.2): Pluecker coordinates and the
// orthonormal representation (U, W) in SO(3) x SO(2) of Bartoli and Sturm ("Structure-from-
// motion using lines", CVIU 2005), with its four-parameter minimal update.
//
// Pluecker convention, as in the thesis (A.13): L = (a, b) with a the direction of the line
// and b = a x P its moment, P any point of the line. (Bartoli and Sturm put the moment
// first; the thesis' order is kept, and U's first column is therefore the direction.)
// Constructors return a with |a| = 1, so |b| is the distance of the line from the origin
// and b x a is the point of the line nearest the origin.
//
// Orthonormal representation (A.14-A.16, with sigma = (|a|, |b|), not the (|a|, |a|)
// misprinted under A.15):
//   U = (a / |a|, b / |b|, a x b / |a x b|),   W = R(alpha),  alpha = atan2(|b|, |a|)
//   L = (w11 u1, w21 u2), here scaled by 1 / w11 so that |a| = 1.
// A line through the origin has b = 0; U's second column is then any unit vector
// orthogonal to a (TangentBasis, so3.hpp) and W = I. The minimal update
// p = (theta_1, theta_2, theta_3, theta) is
//   U <- U exp([theta_1..3]x),   W <- W R(theta)                             (A.17-A.18)
// with exp the SO(3) exponential in place of the thesis' Euler angles (A.11): they agree
// to first order, and exp composes exactly along an axis. theta changes only the distance,
// tan(alpha + theta); the three angles rotate the line about the origin.
//
// Two limits of this chart that the thesis does not mention. It is singular for a line
// through the origin of its frame, like polar coordinates at their centre: theta_1 then
// turns the line about itself and an offset along u3 is of second order, so the factor's
// Jacobian loses rank (tests: LandmarkAnchoredOffTheLineHasAFullRankChart). And theta
// moves a line at distance d by (1 + d^2) theta, so far from the origin the four
// parameters are badly scaled. Both are avoided by keeping a line landmark in a frame
// anchored near where it was seen but off the line, e.g. at the first sensor position
// that observed it (landmark_factors.hpp says how to pass such a frame).
#pragma once

#include <optional>

#include <Eigen/Geometry>

namespace flat2d::localization::landmarks {

// Pluecker coordinates L = (a, b), b = a x P (A.13); |a| = 1 when built by the functions
// below.
struct PluckerLine {
  Eigen::Vector3d a = Eigen::Vector3d::UnitX();  // direction
  Eigen::Vector3d b = Eigen::Vector3d::Zero();   // moment
};

// (U, W) of A.14-A.15.
struct OrthonormalLine {
  Eigen::Matrix3d U = Eigen::Matrix3d::Identity();
  Eigen::Matrix2d W = Eigen::Matrix2d::Identity();
};

// The line through `point` along `direction`. nullopt when the direction is shorter than
// 1e-12 or an input is not finite.
std::optional<PluckerLine> LineFromPointDirection(const Eigen::Vector3d& point,
                                                  const Eigen::Vector3d& direction);

// Raw coordinates (a, b), scaled to |a| = 1. nullopt when a is shorter than 1e-12, an input
// is not finite, or the Pluecker constraint a . b = 0 fails by more than 1e-9 |a| |b|.
std::optional<PluckerLine> LineFromCoordinates(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// The point of the line nearest the origin, b x a / |a|^2.
Eigen::Vector3d ClosestPointToOrigin(const PluckerLine& line);

// The unit direction a / |a|.
Eigen::Vector3d Direction(const PluckerLine& line);

// A.14-A.15.
OrthonormalLine ToOrthonormal(const PluckerLine& line);

// A.16, scaled to |a| = 1. nullopt when |w11| < 1e-12: the line lies at infinity, which
// an update (A.18) can reach but no finite line is.
std::optional<PluckerLine> ToPlucker(const OrthonormalLine& line);

// The line in frame a, given the line in frame b and a_T_b = (R, t):
//   a_a = R a_b,  b_a = R b_b - t x (R a_b)   (for b = a x P; P_a = R P_b + t).
PluckerLine Transformed(const Eigen::Isometry3d& a_T_b, const PluckerLine& line_b);

// A.17-A.18 with delta = (theta_1, theta_2, theta_3, theta). Retract(line, 0) = line.
OrthonormalLine Retract(const OrthonormalLine& line, const Eigen::Vector4d& delta);

// The inverse of A.17-A.18: the delta with Retract(from, delta) = to, for rotations
// between the U's below pi.
Eigen::Vector4d Local(const OrthonormalLine& from, const OrthonormalLine& to);

}  // namespace flat2d::localization::landmarks
