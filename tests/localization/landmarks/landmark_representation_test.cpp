#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "localization/landmarks/line.hpp"
#include "localization/landmarks/plane.hpp"
#include "tests/localization/landmarks/random_geometry.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::RandomOrthogonal;
using testing::RandomPose;
using testing::RandomUnit;
using testing::RandomVector;

constexpr double kPi = 3.14159265358979323846;
constexpr int kRepresentationCases = 200;

// Case i cycles through a generic plane, a horizontal one (the pole of the angles), one
// through the origin and one a hair off horizontal.
Plane PlaneCase(std::mt19937& rng, int i) {
  std::uniform_real_distribution<double> offset(-50.0, 50.0);
  const double up = rng() % 2 == 0 ? 1.0 : -1.0;
  switch (i % 4) {
    case 1: return Plane{Eigen::Vector3d(0.0, 0.0, up), offset(rng)};
    case 2: return Plane{RandomUnit(rng), 0.0};
    // Braces: the draws are made in order (a call's arguments have none).
    case 3: return Plane{Eigen::Vector3d{1e-9 * offset(rng), 1e-9 * offset(rng), up}.normalized(), offset(rng)};
    default: return Plane{RandomUnit(rng), offset(rng)};
  }
}

// Case i cycles through a generic line, one through the origin, one far from it.
PluckerLine LineCase(std::mt19937& rng, int i, Eigen::Vector3d* point, Eigen::Vector3d* direction) {
  *direction = RandomVector(rng, 3.0);
  *point = i % 3 == 1 ? 0.7 * *direction : RandomVector(rng, i % 3 == 2 ? 1e3 : 5.0);
  const std::optional<PluckerLine> line = LineFromPointDirection(*point, *direction);
  EXPECT_TRUE(line.has_value());
  return *line;
}

TEST(PlaneRepresentation, CoefficientsRoundTripThroughHessianAndAngles) {
  const unsigned seed = 1301;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> scale(0.01, 100.0);
  for (int i = 0; i < kRepresentationCases; ++i) {
    const Plane truth = PlaneCase(rng, i);
    const double s = (rng() % 2 == 0 ? 1.0 : -1.0) * scale(rng);
    Eigen::Vector4d abcd;
    abcd << s * truth.normal, s * truth.distance;
    const std::optional<Plane> plane = PlaneFromCoefficients(abcd);
    ASSERT_TRUE(plane.has_value()) << "case " << i;
    const Eigen::Vector4d expected = abcd / abcd.head<3>().norm();
    const PlaneAngles angles = ToAngles(*plane);
    EXPECT_LE((Coefficients(FromAngles(angles)) - expected).norm(), 1e-9) << "case " << i;
    EXPECT_LE((Coefficients(*plane) - expected).norm(), 1e-12) << "case " << i;
    EXPECT_GE(angles.elevation, 0.0);
    EXPECT_LE(angles.elevation, kPi);
    // Every point of the scaled plane satisfies n.x + d = 0.
    const Eigen::Vector3d x = -truth.distance * truth.normal + 7.0 * RandomOrthogonal(rng, truth.normal);
    EXPECT_NEAR(plane->normal.dot(x) + plane->distance, 0.0, 1e-9) << "case " << i;
    if (i % 4 == 1) {
      EXPECT_EQ(angles.azimuth, 0.0) << "a horizontal plane has azimuth 0 by convention";
    }
  }
}

TEST(PlaneRepresentation, AnglesRoundTripAndThePoleConvention) {
  const unsigned seed = 1302;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> azimuth(-kPi + 1e-6, kPi - 1e-6);
  std::uniform_real_distribution<double> elevation(1e-6, kPi - 1e-6);
  std::uniform_real_distribution<double> offset(-50.0, 50.0);
  for (int i = 0; i < kRepresentationCases; ++i) {
    const PlaneAngles angles{azimuth(rng), elevation(rng), offset(rng)};
    const Plane plane = FromAngles(angles);
    EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-12);
    // phi is the angle between the normal and +z; theta that of its horizontal part to +x.
    EXPECT_NEAR(std::acos(std::clamp(plane.normal.z(), -1.0, 1.0)), angles.elevation, 1e-7);
    const PlaneAngles back = ToAngles(plane);
    EXPECT_NEAR(back.azimuth, angles.azimuth, 1e-9) << "case " << i;
    EXPECT_NEAR(back.elevation, angles.elevation, 1e-9) << "case " << i;
    EXPECT_NEAR(back.distance, angles.distance, 1e-12) << "case " << i;
    // At the poles any azimuth names the same plane, and it comes back as 0.
    for (const double pole : {0.0, kPi}) {
      const PlaneAngles at_pole = ToAngles(FromAngles({angles.azimuth, pole, angles.distance}));
      EXPECT_EQ(at_pole.azimuth, 0.0);
      EXPECT_NEAR(at_pole.elevation, pole, 1e-12);
    }
    // A horizontal plane stays at the pole under any yaw, rounding included.
    const Plane yawed = Transformed(testing::Rotation(Eigen::Vector3d::UnitZ(), angles.azimuth),
                                    Plane{Eigen::Vector3d::UnitZ(), angles.distance});
    EXPECT_EQ(ToAngles(yawed).azimuth, 0.0);
  }
}

TEST(PlaneRepresentation, TransformMatchesTransformedPoints) {
  const unsigned seed = 1303;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kRepresentationCases; ++i) {
    const double scale = i % 3 == 0 ? 1e3 : 10.0;
    const Eigen::Isometry3d a_T_b = RandomPose(rng, scale);
    const Plane plane_b = PlaneCase(rng, i);
    const Eigen::Vector3d e1 = RandomOrthogonal(rng, plane_b.normal);
    const Eigen::Vector3d e2 = plane_b.normal.cross(e1);
    const Eigen::Vector3d origin_b = -plane_b.distance * plane_b.normal + RandomVector(rng, 5.0);
    const Eigen::Vector3d on_plane = origin_b - plane_b.normal.dot(origin_b + plane_b.distance * plane_b.normal) * plane_b.normal;
    const Eigen::Vector3d x0 = a_T_b * on_plane;
    const Eigen::Vector3d x1 = a_T_b * (on_plane + 3.0 * e1);
    const Eigen::Vector3d x2 = a_T_b * (on_plane + 4.0 * e2);
    const Plane plane_a = Transformed(a_T_b, plane_b);
    // The plane through the three transformed points, oriented like R n_b.
    Eigen::Vector3d normal = (x1 - x0).cross(x2 - x0).normalized();
    if (normal.dot(a_T_b.linear() * plane_b.normal) < 0.0) normal = -normal;
    EXPECT_LE((plane_a.normal - normal).norm(), 1e-9) << "case " << i;
    for (const Eigen::Vector3d& x : {x0, x1, x2}) {
      EXPECT_NEAR(plane_a.normal.dot(x) + plane_a.distance, 0.0, 1e-9 * scale) << "case " << i;
    }
    const Plane back = Transformed(a_T_b.inverse(), plane_a);
    EXPECT_LE((Coefficients(back) - Coefficients(plane_b)).norm(), 1e-9 * scale) << "case " << i;
  }
}

TEST(PlaneRepresentation, BadCoefficientsAreRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(PlaneFromCoefficients(Eigen::Vector4d(0.0, 0.0, 0.0, 1.0)).has_value());
  EXPECT_FALSE(PlaneFromCoefficients(Eigen::Vector4d::Zero()).has_value());
  EXPECT_FALSE(PlaneFromCoefficients(Eigen::Vector4d(1e-13, 0.0, 0.0, 1.0)).has_value());
  EXPECT_FALSE(PlaneFromCoefficients(Eigen::Vector4d(nan, 0.0, 1.0, 1.0)).has_value());
  EXPECT_FALSE(PlaneFromCoefficients(Eigen::Vector4d(0.0, 0.0, 1.0, inf)).has_value());
  EXPECT_TRUE(PlaneFromCoefficients(Eigen::Vector4d(0.0, 0.0, 1e-6, 1.0)).has_value());
}

TEST(PlaneManifold, ZeroIsIdentityLocalInvertsRetractAndStepsAreGeodesic) {
  const unsigned seed = 1304;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kRepresentationCases; ++i) {
    const Plane plane = PlaneCase(rng, i);
    const Plane same = Retract(plane, Eigen::Vector3d::Zero());
    EXPECT_LE((Coefficients(same) - Coefficients(plane)).norm(), 1e-15);
    const Eigen::Vector3d delta = RandomVector(rng, i % 2 == 0 ? 1.0 : 1e-4);
    const Plane moved = Retract(plane, delta);
    // The normal turns by exactly |delta_12| and the offset moves by delta_d.
    const double turned = std::atan2(plane.normal.cross(moved.normal).norm(), plane.normal.dot(moved.normal));
    EXPECT_NEAR(turned, delta.head<2>().norm(), 1e-12) << "case " << i;
    EXPECT_NEAR(moved.distance - plane.distance, delta(2), 1e-12);
    EXPECT_LE((Local(plane, moved) - delta).norm(), 1e-9) << "case " << i;
    // And back from any other (non-antipodal) plane.
    const Plane other = PlaneCase(rng, i + 1);
    if (other.normal.dot(plane.normal) < -0.99) continue;
    EXPECT_LE((Coefficients(Retract(plane, Local(plane, other))) - Coefficients(other)).norm(), 1e-9) << "case " << i;
  }
}

TEST(LineRepresentation, PointAndDirectionComeBackAsClosestPointAndUnitDirection) {
  const unsigned seed = 1305;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kRepresentationCases; ++i) {
    Eigen::Vector3d point, direction;
    const PluckerLine line = LineCase(rng, i, &point, &direction);
    const Eigen::Vector3d unit = direction.normalized();
    EXPECT_LE((Direction(line) - unit).norm(), 1e-12) << "case " << i;
    EXPECT_NEAR(line.a.norm(), 1.0, 1e-12);
    const Eigen::Vector3d expected = point - unit.dot(point) * unit;  // foot of the perpendicular
    const double scale = std::max(1.0, point.norm());
    EXPECT_LE((ClosestPointToOrigin(line) - expected).norm(), 1e-12 * scale) << "case " << i;
    EXPECT_NEAR(line.b.norm(), expected.norm(), 1e-12 * scale) << "|b| is the distance";
  }
}

TEST(LineRepresentation, PluckerRoundTripsThroughOrthonormal) {
  const unsigned seed = 1306;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kRepresentationCases; ++i) {
    Eigen::Vector3d point, direction;
    const PluckerLine line = LineCase(rng, i, &point, &direction);
    const OrthonormalLine orthonormal = ToOrthonormal(line);
    EXPECT_LE((orthonormal.U.transpose() * orthonormal.U - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(orthonormal.U.determinant(), 1.0, 1e-12);
    EXPECT_LE((orthonormal.W.transpose() * orthonormal.W - Eigen::Matrix2d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(orthonormal.W.determinant(), 1.0, 1e-12);
    // W encodes the distance: w21 / w11 = |b| / |a|.
    EXPECT_NEAR(orthonormal.W(1, 0) / orthonormal.W(0, 0), line.b.norm(), 1e-9 * std::max(1.0, line.b.norm()));
    const std::optional<PluckerLine> back = ToPlucker(orthonormal);
    ASSERT_TRUE(back.has_value());
    const double scale = std::max(1.0, line.b.norm());
    EXPECT_LE((back->a - line.a).norm(), 1e-9) << "case " << i;
    EXPECT_LE((back->b - line.b).norm(), 1e-9 * scale) << "case " << i;
  }
}

TEST(LineRepresentation, TransformMatchesTransformedPoints) {
  const unsigned seed = 1307;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kRepresentationCases; ++i) {
    const double scale = i % 2 == 0 ? 1e3 : 10.0;
    const Eigen::Isometry3d a_T_b = RandomPose(rng, scale);
    Eigen::Vector3d point, direction;
    const PluckerLine line_b = LineCase(rng, i, &point, &direction);
    const Eigen::Vector3d p0 = a_T_b * (point - 2.0 * direction);
    const Eigen::Vector3d p1 = a_T_b * (point + 3.0 * direction);
    const std::optional<PluckerLine> expected = LineFromPointDirection(p0, p1 - p0);
    ASSERT_TRUE(expected.has_value());
    const PluckerLine line_a = Transformed(a_T_b, line_b);
    const double size = std::max(scale, point.norm());
    EXPECT_LE((line_a.a - expected->a).norm(), 1e-9) << "case " << i;
    EXPECT_LE((line_a.b - expected->b).norm(), 1e-9 * size) << "case " << i;
    // Both transformed points satisfy a x p = b.
    EXPECT_LE((line_a.a.cross(p0) - line_a.b).norm(), 1e-9 * size);
    EXPECT_LE((line_a.a.cross(p1) - line_a.b).norm(), 1e-9 * size);
  }
}

TEST(LineRepresentation, BadInputIsRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3d p(1.0, 2.0, 3.0);
  EXPECT_FALSE(LineFromPointDirection(p, Eigen::Vector3d::Zero()).has_value());
  EXPECT_FALSE(LineFromPointDirection(p, Eigen::Vector3d(1e-13, 0.0, 0.0)).has_value());
  EXPECT_FALSE(LineFromPointDirection(Eigen::Vector3d(nan, 0.0, 0.0), Eigen::Vector3d::UnitX()).has_value());
  EXPECT_FALSE(LineFromCoordinates(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()).has_value());
  EXPECT_FALSE(LineFromCoordinates(Eigen::Vector3d::UnitX(), Eigen::Vector3d(1.0, 1.0, 0.0)).has_value())
      << "a moment with a part along the direction is no line";
  const std::optional<PluckerLine> scaled = LineFromCoordinates(Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(0.0, 4.0, 0.0));
  ASSERT_TRUE(scaled.has_value());
  EXPECT_NEAR(scaled->b.norm(), 2.0, 1e-15);
  OrthonormalLine at_infinity;
  at_infinity.W = Eigen::Rotation2Dd(kPi / 2.0).toRotationMatrix();
  EXPECT_FALSE(ToPlucker(at_infinity).has_value());
}

TEST(LineManifold, ZeroIsIdentityStepsComposeAndLocalInvertsRetract) {
  const unsigned seed = 1308;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> fraction(-1.0, 1.0);
  for (int i = 0; i < kRepresentationCases; ++i) {
    Eigen::Vector3d point, direction;
    const OrthonormalLine line = ToOrthonormal(LineCase(rng, i, &point, &direction));
    const OrthonormalLine same = Retract(line, Eigen::Vector4d::Zero());
    EXPECT_LE((same.U - line.U).norm() + (same.W - line.W).norm(), 1e-15);
    Eigen::Vector4d delta;
    delta << RandomVector(rng, 1.0), 0.3 * fraction(rng);
    const double s = fraction(rng);
    const double t = fraction(rng);
    const OrthonormalLine twice = Retract(Retract(line, s * delta), t * delta);
    const OrthonormalLine once = Retract(line, (s + t) * delta);
    EXPECT_LE((twice.U - once.U).norm() + (twice.W - once.W).norm(), 1e-12) << "case " << i;
    EXPECT_LE((Local(line, Retract(line, delta)) - delta).norm(), 1e-9) << "case " << i;
    // theta alone keeps the direction and the plane through the origin, and moves the
    // distance from tan(alpha) to tan(alpha + theta).
    const std::optional<PluckerLine> before = ToPlucker(line);
    const std::optional<PluckerLine> after = ToPlucker(Retract(line, Eigen::Vector4d(0.0, 0.0, 0.0, delta(3))));
    ASSERT_TRUE(before.has_value() && after.has_value());
    EXPECT_LE((after->a - before->a).norm(), 1e-12);
    const double alpha = std::atan(before->b.norm());
    EXPECT_NEAR(std::abs(std::tan(alpha + delta(3))), after->b.norm(), 1e-9 * std::max(1.0, after->b.norm()));
  }
}

}  // namespace
}  // namespace flat2d::localization::landmarks
