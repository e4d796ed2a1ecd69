// Covariance propagation (dead_reckoning.hpp D7, se2.hpp E5) against the closed form of a
// straight drive and against Monte-Carlo runs over seeded noisy measurements: the sample
// covariance of 500 runs must match the propagated one within 15 % on the variances
// (the sample variance alone scatters by sqrt(2/500) = 6 %) and 0.1 on the correlations.
// The same runs check PoseHistory::Between's covariance of the relative motion (H2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "localization/odometry/dead_reckoning.hpp"
#include "localization/odometry/pose_history.hpp"
#include "tests/localization/odometry/synthetic_drive.hpp"

namespace flat2d::localization {
namespace {

using hal::can::OdometryMeasurement;

constexpr unsigned kSeed = 20240611;
constexpr int kRuns = 500;
constexpr double kRateHz = 100.0;
constexpr double kV = 10.0;
constexpr double kW = 0.1;
constexpr double kDurationS = 10.0;
// The relative motion checked: between two times that fall between samples.
constexpr TimeNs kA = 3 * kNsPerSecond + 4 * kNsPerMs;
constexpr TimeNs kB = 8 * kNsPerSecond + 7 * kNsPerMs;

Eigen::Matrix3d SampleCovariance(const std::vector<Se2>& poses) {
  Eigen::Vector2d mean_xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_direction = Eigen::Vector2d::Zero();
  for (const Se2& pose : poses) {
    mean_xy += pose.translation();
    mean_direction += Eigen::Vector2d(std::cos(pose.theta()), std::sin(pose.theta()));
  }
  const Se2 mean(mean_xy / static_cast<double>(poses.size()),
                 std::atan2(mean_direction.y(), mean_direction.x()));
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Se2& pose : poses) {
    const Eigen::Vector3d d = ComponentDifference(pose, mean);
    covariance += d * d.transpose();
  }
  return covariance / static_cast<double>(poses.size() - 1);
}

void ExpectCovarianceMatches(const Eigen::Matrix3d& sample, const Eigen::Matrix3d& predicted,
                             const char* what) {
  const char* names[] = {"x", "y", "theta"};
  for (int i = 0; i < 3; ++i) {
    const double ratio = sample(i, i) / predicted(i, i);
    std::printf("  %s: std(%s) sample %.4g predicted %.4g, variance ratio %.3f\n", what, names[i],
                std::sqrt(sample(i, i)), std::sqrt(predicted(i, i)), ratio);
    EXPECT_NEAR(ratio, 1.0, 0.15) << what << " " << names[i];
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      const double sample_rho = sample(i, j) / std::sqrt(sample(i, i) * sample(j, j));
      const double predicted_rho = predicted(i, j) / std::sqrt(predicted(i, i) * predicted(j, j));
      std::printf("  %s: corr(%s, %s) sample %+.3f predicted %+.3f\n", what, names[i], names[j],
                  sample_rho, predicted_rho);
      EXPECT_NEAR(sample_rho, predicted_rho, 0.1) << what << " " << names[i] << names[j];
    }
  }
}

struct Noise {
  double speed = 0.0;     // m/sqrt(s), on vehicle_speed
  double wheel = 0.0;     // m/sqrt(s), on each wheel
  double yaw_rate = 0.0;  // rad/sqrt(s)
};

struct DriveResult {
  OdometrySample last;
  RelativeMotion relative;
};

// One drive; each sample's noise has the density / sqrt(dt) a white input would average to.
DriveResult Drive(const DeadReckoningOptions& options, const testing::Sensors& sensors,
                  const Noise& noise, std::mt19937& rng) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const double per_sample = std::sqrt(kRateHz);
  auto odometry = DeadReckoning::Create(options);
  auto history = PoseHistory::Create({.capacity = 2048, .max_extrapolation_ns = 0});
  EXPECT_TRUE(odometry.ok() && history.ok());
  for (OdometryMeasurement m : testing::SampleDrive({{kV, kW, kDurationS}}, kRateHz, sensors)) {
    if (m.vehicle_speed_mps) *m.vehicle_speed_mps += noise.speed * per_sample * unit(rng);
    if (m.yaw_rate_radps) *m.yaw_rate_radps += noise.yaw_rate * per_sample * unit(rng);
    if (m.wheel_speeds) {
      m.wheel_speeds->rear_left_mps += noise.wheel * per_sample * unit(rng);
      m.wheel_speeds->rear_right_mps += noise.wheel * per_sample * unit(rng);
    }
    history->Push(odometry->Update(m).sample);
  }
  return {odometry->latest(), history->Between(kA, kB)};
}

void MonteCarlo(const DeadReckoningOptions& options, const testing::Sensors& sensors,
                const Noise& noise) {
  std::printf("  seed %u, %d runs\n", kSeed, kRuns);
  std::mt19937 rng(kSeed);
  const DriveResult reference = Drive(options, sensors, Noise{}, rng);
  ASSERT_TRUE(reference.relative.ok());
  std::vector<Se2> finals;
  std::vector<Se2> relatives;
  for (int run = 0; run < kRuns; ++run) {
    const DriveResult noisy = Drive(options, sensors, noise, rng);
    finals.push_back(noisy.last.local_T_vehicle);
    relatives.push_back(noisy.relative.a_T_b);
  }
  ExpectCovarianceMatches(SampleCovariance(finals), reference.last.covariance, "final pose");
  ExpectCovarianceMatches(SampleCovariance(relatives), reference.relative.covariance,
                          "relative motion");
}

TEST(OdometryCovariance, MonteCarloWithYawRateSensorAndVehicleSpeed) {
  DeadReckoningOptions options;
  options.speed_noise_m_per_sqrt_s = 0.05;
  options.yaw_rate_noise_rad_per_sqrt_s = 0.002;
  MonteCarlo(options, {.wheels = false, .yaw_rate = true, .vehicle_speed = true},
             {.speed = 0.05, .yaw_rate = 0.002});
}

TEST(OdometryCovariance, MonteCarloWithWheelSpeedsOnly) {
  DeadReckoningOptions options;
  options.wheel_speed_noise_m_per_sqrt_s = 0.01;
  MonteCarlo(options, {.wheels = true, .yaw_rate = false}, {.wheel = 0.01});
}

// Straight at speed v for T: var(x) = q_v T, var(theta) = q_w T, var(y) = v^2 q_w T^3 / 3,
// cov(y, theta) = v q_w T^2 / 2 (integrals of the heading random walk).
TEST(OdometryCovariance, StraightDriveMatchesTheContinuousTimeClosedForm) {
  DeadReckoningOptions options;
  options.speed_noise_m_per_sqrt_s = 0.05;
  options.yaw_rate_noise_rad_per_sqrt_s = 0.002;
  auto odometry = DeadReckoning::Create(options);
  ASSERT_TRUE(odometry.ok());
  for (const OdometryMeasurement& m :
       testing::SampleDrive({{kV, 0.0, kDurationS}}, kRateHz,
                            {.wheels = false, .yaw_rate = true, .vehicle_speed = true})) {
    odometry->Update(m);
  }
  const double q_v = 0.05 * 0.05;
  const double q_w = 0.002 * 0.002;
  const double t = kDurationS;
  Eigen::Matrix3d expected;
  expected << q_v * t, 0.0, 0.0,                                     //
      0.0, kV * kV * q_w * t * t * t / 3.0, kV * q_w * t * t / 2.0,  //
      0.0, kV * q_w * t * t / 2.0, q_w * t;
  const Eigen::Matrix3d& actual = odometry->latest().covariance;
  std::printf("  var(y) propagated %.6g, closed form %.6g\n", actual(1, 1), expected(1, 1));
  EXPECT_NEAR(actual(0, 0), expected(0, 0), 1e-9 * expected(0, 0));
  EXPECT_NEAR(actual(2, 2), expected(2, 2), 1e-9 * expected(2, 2));
  EXPECT_NEAR(actual(1, 1), expected(1, 1), 1e-3 * expected(1, 1));  // discretisation
  EXPECT_NEAR(actual(1, 2), expected(1, 2), 1e-3 * expected(1, 2));
  EXPECT_NEAR(actual(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(actual(0, 2), 0.0, 1e-12);
}

}  // namespace
}  // namespace flat2d::localization
