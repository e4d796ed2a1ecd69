// The pieces under landmark SLAM: odometry and vehicle-pose observation Jacobians against
// central differences, the planar odometry information, the feature covariance carried
// into the factors' error coordinates (against Monte Carlo), and the robust kernels.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "localization/landmarks/feature_measurement.hpp"
#include "localization/landmarks/graph_factors.hpp"
#include "localization/landmarks/robust_kernel.hpp"
#include "tests/localization/landmarks/random_geometry.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::CentralDifference;
using testing::JacobiansAgree;
using testing::RandomOrthogonal;
using testing::RandomPose;
using testing::RandomUnit;
using testing::RandomVector;

// A small motion: what the odometry measures between two keyframes.
Eigen::Isometry3d SmallMotion(std::mt19937& rng, double scale) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(scale * 0.3, RandomUnit(rng)).toRotationMatrix();
  motion.translation() = RandomVector(rng, scale);
  return motion;
}

TEST(OdometryFactor, JacobiansMatchCentralDifferences) {
  const unsigned seed = 3401;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Isometry3d from = RandomPose(rng, i % 3 == 0 ? 1e3 : 10.0);
    const Eigen::Isometry3d measured = SmallMotion(rng, 1.0);
    // Exactly consistent (error 0) and off by a small odometry error.
    const bool exact = i % 2 == 0;
    const Eigen::Isometry3d to = from * measured * (exact ? Eigen::Isometry3d::Identity() : SmallMotion(rng, 0.01));
    const OdometryLinearization lin = LinearizeOdometry(from, to, measured);
    const auto numeric_from = CentralDifference<6, 6>(
        [&](const Vector6d& d) { return OdometryError(RetractPose(from, d), to, measured); }, 1e-6);
    const auto numeric_to = CentralDifference<6, 6>(
        [&](const Vector6d& d) { return OdometryError(from, RetractPose(to, d), measured); }, 1e-6);
    // J_r^-1 = I is exact at zero error and off by about |e| / 2 otherwise.
    const double tolerance = exact ? 1e-5 : 1e-2;
    EXPECT_TRUE(JacobiansAgree(lin.jacobian_from, numeric_from, tolerance)) << "case " << i << "\n" << lin.jacobian_from << "\n\n" << numeric_from;
    EXPECT_TRUE(JacobiansAgree(lin.jacobian_to, numeric_to, tolerance)) << "case " << i;
    if (exact) {
      EXPECT_LE(lin.error.norm(), 1e-9);
    }
  }
}

TEST(OdometryFactor, InformationIsTightOffThePlaneAndGrowsLooserWithMotion) {
  const OdometryNoise noise;
  Eigen::Isometry3d short_step = Eigen::Isometry3d::Identity(), long_step = Eigen::Isometry3d::Identity();
  short_step.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
  long_step.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  const Matrix6d near = OdometryInformation(short_step, noise), far = OdometryInformation(long_step, noise);
  EXPECT_NEAR(1.0 / std::sqrt(near(0, 0)), 0.5 * noise.translation_sigma_per_m, 1e-12);
  EXPECT_NEAR(1.0 / std::sqrt(near(2, 2)), noise.z_sigma_m, 1e-12);
  EXPECT_NEAR(1.0 / std::sqrt(near(3, 3)), noise.roll_pitch_sigma_rad, 1e-12);
  EXPECT_GT(near(2, 2), 10.0 * near(0, 0)) << "z must be held far tighter than x";
  EXPECT_NEAR(far(0, 0) * 16.0, near(0, 0), 1e-9 * near(0, 0));
  EXPECT_NEAR(1.0 / std::sqrt(OdometryInformation(Eigen::Isometry3d::Identity(), noise)(0, 0)),
              noise.translation_sigma_min_m, 1e-12);
}

TEST(ObservationFactors, VehiclePoseJacobiansMatchCentralDifferences) {
  const unsigned seed = 3402;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < 50; ++i) {
    ObservationGeometry g;
    g.world_T_vehicle = RandomPose(rng, 100.0);
    g.vehicle_T_sensor = RandomPose(rng, 2.0);
    g.world_T_anchor.translation() = RandomVector(rng, 100.0);
    g.sensor_of_vehicle = SensorPerturbationOfVehicle(g.vehicle_T_sensor);
    const Plane plane{RandomUnit(rng), 5.0 * RandomVector(rng, 1.0).x()};
    const Plane measured{RandomUnit(rng), 3.0};
    const PlaneFactorLinearization p = LinearizePlaneObservation(g, plane, measured);
    const auto numeric_plane = CentralDifference<3, 6>(
        [&](const Vector6d& d) {
          ObservationGeometry moved = g;
          moved.world_T_vehicle = RetractPose(g.world_T_vehicle, d);
          return PlaneError(moved.AnchorTSensor(), plane, measured);
        },
        1e-6);
    EXPECT_TRUE(JacobiansAgree(p.jacobian_pose, numeric_plane, 1e-5)) << "case " << i;
    const OrthonormalLine line = ToOrthonormal(*LineFromPointDirection(RandomVector(rng, 5.0), RandomUnit(rng)));
    const PluckerLine seen = *LineFromPointDirection(RandomVector(rng, 5.0), RandomUnit(rng));
    const std::optional<LineFactorLinearization> l = LinearizeLineObservation(g, line, seen);
    ASSERT_TRUE(l.has_value());
    const auto numeric_line = CentralDifference<4, 6>(
        [&](const Vector6d& d) {
          ObservationGeometry moved = g;
          moved.world_T_vehicle = RetractPose(g.world_T_vehicle, d);
          return *LineError(moved.AnchorTSensor(), line, seen);
        },
        1e-6);
    EXPECT_TRUE(JacobiansAgree(l->jacobian_pose, numeric_line, 1e-5)) << "case " << i;
  }
}

// Sample covariance of `samples` error vectors.
template <int D>
Eigen::Matrix<double, D, D> Covariance(const std::vector<Eigen::Matrix<double, D, 1>>& samples) {
  Eigen::Matrix<double, D, D> c = Eigen::Matrix<double, D, D>::Zero();
  for (const auto& e : samples) c += e * e.transpose();
  return c / static_cast<double>(samples.size());
}

// A sample's error is in its own measurement's tangent basis B(m) (so3.hpp), the prediction
// in B of the unperturbed feature. B turns quickly with m near the z axis (unitOrthogonal
// takes the x-y part), so the sampled errors are turned into the feature's basis first;
// otherwise the comparison holds only for directions far from z.
Eigen::Matrix2d IntoBasisOf(const Eigen::Vector3d& feature_axis, const Eigen::Vector3d& sampled_axis) {
  return TangentBasis(feature_axis).transpose() * TangentBasis(sampled_axis);
}

TEST(FeatureMeasurement, PlaneCovarianceIsCarriedIntoTheFactorError) {
  const unsigned seed = 3403;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  maps::features3d::PlaneFeature f;
  f.normal = RandomUnit(rng);
  f.major_axis = RandomOrthogonal(rng, f.normal);
  f.centroid = Eigen::Vector3d(8.0, -3.0, 1.0);
  f.d = -f.normal.dot(f.centroid);
  const Eigen::Vector3d sigma(0.02, 0.01, 0.05);  // tilts towards u2, u3; offset at the centroid
  f.covariance = sigma.cwiseAbs2().asDiagonal();
  const std::optional<PlaneMeasurement> m = PlaneMeasurementOf(f, MeasurementFloors{0.0, 0.0, 0.0, 0.0});
  ASSERT_TRUE(m.has_value());
  const Eigen::Vector3d u3 = f.major_axis, u2 = f.normal.cross(u3);
  std::vector<Eigen::Vector3d> errors;
  for (int s = 0; s < 40000; ++s) {  // the measured plane perturbed as the feature's covariance says
    const Eigen::Vector3d n = (f.normal + sigma(0) * g(rng) * u2 + sigma(1) * g(rng) * u3).normalized();
    const Eigen::Vector3d c = f.centroid + sigma(2) * g(rng) * f.normal;
    Eigen::Vector3d e = PlaneError(Eigen::Isometry3d::Identity(), Plane{f.normal, f.d}, Plane{n, -n.dot(c)});
    e.head<2>() = IntoBasisOf(f.normal, n) * e.head<2>();
    errors.push_back(e);
  }
  const Eigen::Matrix3d expected = m->information.inverse(), sampled = Covariance<3>(errors);
  EXPECT_LE((sampled - expected).norm(), 0.03 * expected.norm()) << "sampled\n" << sampled << "\nexpected\n" << expected;
}

TEST(FeatureMeasurement, LineCovarianceIsCarriedIntoTheFactorError) {
  const unsigned seed = 3404;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  maps::features3d::LineFeature f;
  f.direction = (Eigen::Vector3d::UnitZ() + 0.2 * RandomUnit(rng)).normalized();
  f.across = RandomOrthogonal(rng, f.direction);
  f.point = Eigen::Vector3d(6.0, 4.0, 2.5);  // far from the point nearest the sensor
  const Eigen::Vector4d sigma(0.03, 0.01, 0.02, 0.005);  // offsets along u1, u2; tilts towards u1, u2
  f.covariance = sigma.cwiseAbs2().asDiagonal();
  const std::optional<LineMeasurement> m = LineMeasurementOf(f, MeasurementFloors{0.0, 0.0, 0.0, 0.0});
  ASSERT_TRUE(m.has_value());
  const Eigen::Vector3d u1 = f.across, u2 = f.direction.cross(u1);
  const OrthonormalLine truth = ToOrthonormal(*LineFromPointDirection(f.point, f.direction));
  std::vector<Eigen::Vector4d> errors;
  for (int s = 0; s < 40000; ++s) {
    const Eigen::Vector3d p = f.point + sigma(0) * g(rng) * u1 + sigma(1) * g(rng) * u2;
    const Eigen::Vector3d a = (f.direction + sigma(2) * g(rng) * u1 + sigma(3) * g(rng) * u2).normalized();
    Eigen::Vector4d e = *LineError(Eigen::Isometry3d::Identity(), truth, *LineFromPointDirection(p, a));
    const Eigen::Matrix2d into_feature = IntoBasisOf(f.direction, a);
    e.head<2>() = into_feature * e.head<2>();
    e.tail<2>() = into_feature * e.tail<2>();
    errors.push_back(e);
  }
  const Eigen::Matrix4d expected = m->information.inverse(), sampled = Covariance<4>(errors);
  EXPECT_LE((sampled - expected).norm(), 0.03 * expected.norm()) << "sampled\n" << sampled << "\nexpected\n" << expected;
}

TEST(FeatureMeasurement, FloorsBoundTheInformationAndBadFeaturesAreRefused) {
  maps::features3d::PlaneFeature plane;
  plane.centroid = Eigen::Vector3d(5.0, 0.0, 0.0);
  plane.normal = -Eigen::Vector3d::UnitX();
  plane.d = 5.0;
  plane.covariance.setZero();  // a "perfect" fit
  const MeasurementFloors floors;
  const std::optional<PlaneMeasurement> m = PlaneMeasurementOf(plane, floors);
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->information(2, 2), 1.0 / (floors.plane_offset_sigma_m * floors.plane_offset_sigma_m), 1e-6);
  plane.normal = Eigen::Vector3d(0.5, 0.0, 0.0);  // not a unit normal
  EXPECT_FALSE(PlaneMeasurementOf(plane, floors).has_value());
  maps::features3d::LineFeature line;
  line.point = Eigen::Vector3d(std::nan(""), 0.0, 0.0);
  EXPECT_FALSE(LineMeasurementOf(line, floors).has_value());
}

TEST(RobustKernel, WeightsAreTheDerivativeOfTheCost) {
  for (const RobustKernel kernel : {RobustKernel::kNone, RobustKernel::kHuber, RobustKernel::kCauchy}) {
    for (const double s : {0.5, 4.0, 30.0, 400.0}) {
      const double h = 1e-6 * s;
      const double derivative = (ApplyKernel(kernel, 3.0, s + h).cost - ApplyKernel(kernel, 3.0, s - h).cost) / (2.0 * h);
      EXPECT_NEAR(ApplyKernel(kernel, 3.0, s).weight, derivative, 1e-6);
    }
  }
  EXPECT_LT(ApplyKernel(RobustKernel::kCauchy, 3.0, 400.0).weight, 0.03);  // ~7 sigma
}

}  // namespace
}  // namespace flat2d::localization::landmarks
