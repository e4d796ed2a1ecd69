#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "localization/landmarks/landmark_factors.hpp"
#include "tests/localization/landmarks/random_geometry.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::CentralDifference;
using testing::JacobiansAgree;
using testing::RandomOrthogonal;
using testing::RandomPose;
using testing::RandomUnit;
using testing::RandomVector;
using testing::TranslationScale;

constexpr int kFactorCases = 100;

// Generic, horizontal (the pole of the angle form) and through-the-origin world planes.
Plane WorldPlane(std::mt19937& rng, int i) {
  std::uniform_real_distribution<double> offset(-30.0, 30.0);
  if (i % 4 == 1) return Plane{Eigen::Vector3d(0.0, 0.0, rng() % 2 == 0 ? 1.0 : -1.0), offset(rng)};
  return Plane{RandomUnit(rng), i % 4 == 2 ? 0.0 : offset(rng)};
}

// The world plane seen from the sensor, from three of its points moved into the sensor
// frame: independent of Transformed().
Plane SeenFrom(std::mt19937& rng, const Eigen::Isometry3d& world_T_sensor, const Plane& world) {
  const Eigen::Vector3d e1 = RandomOrthogonal(rng, world.normal);
  const Eigen::Vector3d e2 = world.normal.cross(e1);
  const Eigen::Isometry3d sensor_T_world = world_T_sensor.inverse();
  const Eigen::Vector3d x0 = sensor_T_world * (-world.distance * world.normal);
  const Eigen::Vector3d x1 = sensor_T_world * (-world.distance * world.normal + e1);
  const Eigen::Vector3d x2 = sensor_T_world * (-world.distance * world.normal + e2);
  const Eigen::Vector3d normal = (x1 - x0).cross(x2 - x0).normalized();
  return Plane{normal, -normal.dot(x0)};
}

TEST(PoseRetraction, PerturbsOnTheRightInTheSensorFrame) {
  const unsigned seed = 1310;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const Eigen::Vector3d dt = RandomVector(rng, 1.0);
    const Eigen::Vector3d axis = RandomUnit(rng);
    const double angle = 0.5 * RandomVector(rng, 1.0).x();
    const Eigen::Isometry3d moved = RetractPose(world_T_sensor, (Vector6d() << dt, angle * axis).finished());
    // dt is a step in the sensor's own axes; dtheta turns the sensor about its own origin.
    EXPECT_LE((moved.translation() - world_T_sensor.translation() - world_T_sensor.linear() * dt).norm(), 1e-9);
    const Eigen::Matrix3d expected = world_T_sensor.linear() * Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    EXPECT_LE((moved.linear() - expected).norm(), 1e-12) << "case " << i;
    EXPECT_LE((RetractPose(world_T_sensor, Vector6d::Zero()).matrix() - world_T_sensor.matrix()).norm(), 1e-15);
  }
}

TEST(PlaneFactor, ZeroAtTruthWhicheverWayTheNormalsPoint) {
  const unsigned seed = 1311;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const Plane world = WorldPlane(rng, i);
    const Plane measured = SeenFrom(rng, world_T_sensor, world);
    const double tolerance = 1e-9 * TranslationScale(i);
    EXPECT_LE(PlaneError(world_T_sensor, world, measured).norm(), tolerance) << "case " << i;
    const Plane flipped{-measured.normal, -measured.distance};
    EXPECT_LE(PlaneError(world_T_sensor, world, flipped).norm(), tolerance) << "case " << i;
    const Plane world_flipped{-world.normal, -world.distance};
    EXPECT_LE(PlaneError(world_T_sensor, world_flipped, measured).norm(), tolerance) << "case " << i;
  }
}

TEST(PlaneFactor, ErrorMeasuresKnownMotionsOfTheSensor) {
  const unsigned seed = 1312;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> amount(-0.5, 0.5);
  for (int i = 0; i < kFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const Plane world = WorldPlane(rng, i);
    const Plane measured = SeenFrom(rng, world_T_sensor, world);
    const double tolerance = 1e-9 * TranslationScale(i);
    // Stepping s along the measured normal moves the plane's offset by s, nothing else.
    const double s = amount(rng);
    Eigen::Isometry3d moved = world_T_sensor;
    moved.translation() += s * (world_T_sensor.linear() * measured.normal);
    const Eigen::Vector3d shifted = PlaneError(moved, world, measured);
    EXPECT_LE(shifted.head<2>().norm(), tolerance) << "case " << i;
    EXPECT_NEAR(shifted(2), s, tolerance) << "case " << i;
    // Turning by beta about an axis in the plane tilts the normal by beta: |e_n| = sin beta,
    // and the offset, measured from the unmoved sensor origin, stays.
    const double beta = amount(rng);
    const Eigen::Isometry3d turned = world_T_sensor * testing::Rotation(RandomOrthogonal(rng, measured.normal), beta);
    const Eigen::Vector3d tilted = PlaneError(turned, world, measured);
    EXPECT_NEAR(tilted.head<2>().norm(), std::abs(std::sin(beta)), 1e-9) << "case " << i;
    EXPECT_NEAR(tilted(2), 0.0, tolerance) << "case " << i;
  }
}

TEST(PlaneFactor, ErrorGrowsWithThePerturbation) {
  const unsigned seed = 1313;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const Plane world = WorldPlane(rng, i);
    const Plane measured = SeenFrom(rng, world_T_sensor, world);
    const Vector6d pose_step = (Vector6d() << RandomVector(rng, 1.0), RandomVector(rng, 1.0)).finished();
    const Eigen::Vector3d plane_step = RandomVector(rng, 1.0);
    double pose_previous = 0.0;
    double plane_previous = 0.0;
    // Steps small enough that a turn of the normal about the world origin, up to 1 km
    // away, stays a fraction of a radian.
    for (const double size : {1e-6, 1e-5, 1e-4, 1e-3}) {
      const double pose_error = PlaneError(RetractPose(world_T_sensor, size * pose_step), world, measured).norm();
      const double plane_error = PlaneError(world_T_sensor, Retract(world, size * plane_step), measured).norm();
      EXPECT_GT(pose_error, pose_previous) << "case " << i << " step " << size;
      EXPECT_GT(plane_error, plane_previous) << "case " << i << " step " << size;
      pose_previous = pose_error;
      plane_previous = plane_error;
    }
  }
}

TEST(PlaneFactor, AnalyticJacobiansEqualCentralDifferences) {
  const unsigned seed = 1314;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < kFactorCases; ++i) {
    const Eigen::Isometry3d world_T_sensor = RandomPose(rng, TranslationScale(i));
    const Plane world = WorldPlane(rng, i);
    // Away from the solution, where the error's own terms are non-zero too, and in every
    // other case with the normal the other way round, which flips the prediction (F2's s).
    Plane measured = Retract(SeenFrom(rng, world_T_sensor, world), RandomVector(rng, 0.2));
    if (i % 2 == 1) measured = Plane{-measured.normal, -measured.distance};
    const PlaneFactorLinearization linear = LinearizePlane(world_T_sensor, world, measured);
    EXPECT_LE((linear.error - PlaneError(world_T_sensor, world, measured)).norm(), 1e-12);
    const auto by_pose = [&](const Vector6d& step) {
      return PlaneError(RetractPose(world_T_sensor, step), world, measured);
    };
    const auto by_plane = [&](const Eigen::Vector3d& step) {
      return PlaneError(world_T_sensor, Retract(world, step), measured);
    };
    const Eigen::Matrix<double, 3, 6> numeric_pose = CentralDifference<3, 6>(by_pose, 1e-6);
    const Eigen::Matrix3d numeric_plane = CentralDifference<3, 3>(by_plane, 1e-6);
    EXPECT_TRUE(JacobiansAgree(linear.jacobian_pose, numeric_pose, 1e-6))
        << "case " << i << "\nanalytic\n" << linear.jacobian_pose << "\nnumeric\n" << numeric_pose;
    EXPECT_TRUE(JacobiansAgree(linear.jacobian_plane, numeric_plane, 1e-6))
        << "case " << i << "\nanalytic\n" << linear.jacobian_plane << "\nnumeric\n" << numeric_plane;
    // No singular chart, horizontal planes included: the Jacobian is block triangular with
    // B(n_m)^T R^T B(n_w), a 2x2 rotation at agreement, and 1 on the diagonal, so its
    // determinant is the cosine of the (at most 0.35 rad) angle between the normals.
    EXPECT_GT(std::abs(linear.jacobian_plane.determinant()), 0.9) << "case " << i;
  }
}

}  // namespace
}  // namespace flat2d::localization::landmarks
