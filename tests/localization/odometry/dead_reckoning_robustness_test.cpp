// Bad input to dead reckoning is counted and harmless: non-finite values, duplicate and
// out-of-order times, gaps, missing inputs; and the yaw-rate bias is removed when configured
// or estimated while standing still.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "localization/odometry/dead_reckoning.hpp"
#include "tests/localization/odometry/synthetic_drive.hpp"

namespace flat2d::localization {
namespace {

using hal::can::OdometryMeasurement;
using testing::ClosedFormArc;

constexpr double kV = 10.0;
constexpr double kW = 0.2;
constexpr TimeNs kPeriod = 10 * kNsPerMs;

std::vector<OdometryMeasurement> CleanArc() {
  return testing::SampleDrive({{kV, kW, 10.0}}, 100.0, {});
}

DeadReckoning Make(const DeadReckoningOptions& options = {}) {
  auto odometry = DeadReckoning::Create(options);
  EXPECT_TRUE(odometry.ok());
  return std::move(odometry.value());
}

// Feeds everything; returns the final sample and checks time never went backwards.
OdometrySample Feed(DeadReckoning& odometry, const std::vector<OdometryMeasurement>& drive) {
  TimeNs last = std::numeric_limits<TimeNs>::min();
  for (const OdometryMeasurement& m : drive) {
    const DeadReckoningUpdate update = odometry.Update(m);
    EXPECT_GE(update.sample.time_ns, last);
    last = update.sample.time_ns;
  }
  return odometry.latest();
}

void ExpectSamePose(const OdometrySample& a, const OdometrySample& b) {
  EXPECT_EQ(a.time_ns, b.time_ns);
  EXPECT_LT(ComponentDifference(a.local_T_vehicle, b.local_T_vehicle).norm(), 1e-12);
  EXPECT_LT((a.covariance - b.covariance).norm(), 1e-15);
}

TEST(DeadReckoningRobustness, NonFiniteMeasurementsAreDroppedAndCounted) {
  DeadReckoning clean = Make();
  const OdometrySample reference = Feed(clean, CleanArc());
  std::vector<OdometryMeasurement> drive;
  for (const OdometryMeasurement& m : CleanArc()) {
    OdometryMeasurement bad = m;
    bad.time_ns += kPeriod / 2;
    bad.yaw_rate_radps = std::numeric_limits<double>::quiet_NaN();
    drive.push_back(m);
    drive.push_back(bad);
  }
  // Every odd entry is bad; three of them in another field than the yaw rate.
  for (std::size_t i : {3u, 5u, 7u}) drive[i].yaw_rate_radps = kW;
  drive[3].wheel_speeds->front_left_mps = std::numeric_limits<double>::infinity();
  drive[5].vehicle_speed_mps = -std::numeric_limits<double>::infinity();
  drive[7].steering_angle_rad = std::numeric_limits<double>::quiet_NaN();
  DeadReckoning odometry = Make();
  ExpectSamePose(Feed(odometry, drive), reference);
  EXPECT_EQ(odometry.stats().non_finite, drive.size() / 2);
}

TEST(DeadReckoningRobustness, DuplicateTimesAreMergedWithoutAStep) {
  DeadReckoning clean = Make();
  const OdometrySample reference = Feed(clean, CleanArc());
  std::vector<OdometryMeasurement> drive;
  for (const OdometryMeasurement& m : CleanArc()) {
    drive.push_back(m);
    drive.push_back(m);
  }
  DeadReckoning odometry = Make();
  ExpectSamePose(Feed(odometry, drive), reference);
  EXPECT_EQ(odometry.stats().duplicate_times, CleanArc().size());
  EXPECT_EQ(odometry.stats().steps, CleanArc().size() - 1);
}

TEST(DeadReckoningRobustness, OutOfOrderMeasurementsAreDroppedAndNeverMoveBackwards) {
  DeadReckoning clean = Make();
  const OdometrySample reference = Feed(clean, CleanArc());
  std::vector<OdometryMeasurement> drive;
  std::uint64_t late = 0;
  for (const OdometryMeasurement& m : CleanArc()) {
    drive.push_back(m);
    if (drive.size() > 20 && drive.size() % 7 == 0) {
      OdometryMeasurement stale = drive[drive.size() - 15];
      stale.yaw_rate_radps = -1.0;  // would bend the path if it were used
      drive.push_back(stale);
      ++late;
    }
  }
  DeadReckoning odometry = Make();
  ExpectSamePose(Feed(odometry, drive), reference);
  EXPECT_EQ(odometry.stats().out_of_order, late);
}

// A 1 s hole in the data, longer than max_gap_ns (0.2 s).
std::vector<OdometryMeasurement> ArcWithHole() {
  std::vector<OdometryMeasurement> drive;
  for (const OdometryMeasurement& m : CleanArc()) {
    if (m.time_ns <= 3 * kNsPerSecond || m.time_ns >= 4 * kNsPerSecond) drive.push_back(m);
  }
  return drive;
}

TEST(DeadReckoningRobustness, GapIsHeldAndMarkedByDefault) {
  DeadReckoning odometry = Make();
  Se2 before_gap;
  for (const OdometryMeasurement& m : ArcWithHole()) {
    const DeadReckoningUpdate update = odometry.Update(m);
    if (m.time_ns == 3 * kNsPerSecond) before_gap = update.sample.local_T_vehicle;
    if (m.time_ns == 4 * kNsPerSecond) {
      EXPECT_TRUE(update.sample.discontinuity);
      EXPECT_LT(ComponentDifference(update.sample.local_T_vehicle, before_gap).norm(), 1e-15);
      EXPECT_EQ(update.sample.step_covariance, Eigen::Matrix3d::Zero());
    } else {
      EXPECT_FALSE(update.sample.discontinuity) << m.time_ns;
    }
  }
  EXPECT_EQ(odometry.stats().gaps, 1u);
  // After the gap the motion is right again: the last 6 s match the closed form.
  const Se2 expected_tail = ClosedFormArc(kV, kW, 6.0);
  const Se2 actual_tail = before_gap.Inverse() * odometry.latest().local_T_vehicle;
  EXPECT_LT(ComponentDifference(actual_tail, expected_tail).norm(), 1e-6);
}

TEST(DeadReckoningRobustness, GapExtrapolatesTheLastMotionWhenAsked) {
  DeadReckoningOptions options;
  options.gap_policy = GapPolicy::kExtrapolate;
  DeadReckoning odometry = Make(options);
  const OdometrySample last = Feed(odometry, ArcWithHole());
  EXPECT_EQ(odometry.stats().gaps, 1u);
  // Constant inputs: the extrapolation is exact.
  EXPECT_LT(testing::PositionError(last.local_T_vehicle, ClosedFormArc(kV, kW, 10.0)), 1e-6);
}

TEST(DeadReckoningRobustness, StaleYawRateSensorFallsBackToWheelSpeeds) {
  std::vector<OdometryMeasurement> drive = CleanArc();
  for (OdometryMeasurement& m : drive) {
    if (m.time_ns > 5 * kNsPerSecond) m.yaw_rate_radps.reset();  // the sensor frame stops
  }
  DeadReckoning odometry = Make();
  const OdometrySample last = Feed(odometry, drive);
  // Fresh for max_gap_ns (0.2 s) inclusive: the steps starting at 5.00 ... 5.20 s still use
  // the held value, the other 479 of the second half the wheels.
  EXPECT_EQ(odometry.stats().wheel_yaw_rate_steps, 500u - 21u);
  EXPECT_LT(testing::PositionError(last.local_T_vehicle, ClosedFormArc(kV, kW, 10.0)), 1e-6);
}

TEST(DeadReckoningRobustness, WithoutSpeedThePoseIsHeldAndMarked) {
  DeadReckoning odometry = Make();
  for (const OdometryMeasurement& m :
       testing::SampleDrive({{kV, kW, 1.0}}, 100.0, {.wheels = false, .yaw_rate = true})) {
    odometry.Update(m);
  }
  EXPECT_EQ(odometry.stats().steps_without_input, 100u);
  EXPECT_TRUE(odometry.latest().discontinuity);
  EXPECT_EQ(odometry.latest().local_T_vehicle.Vector(), Eigen::Vector3d::Zero());
}

// Yaw-rate sensor reading w + 0.02 rad/s.
std::vector<OdometryMeasurement> BiasedDrive(double standstill_s, double drive_s) {
  std::vector<OdometryMeasurement> drive =
      testing::SampleDrive({{0.0, 0.0, standstill_s}, {kV, kW, drive_s}}, 100.0, {});
  for (OdometryMeasurement& m : drive) *m.yaw_rate_radps += 0.02;
  return drive;
}

TEST(DeadReckoningBias, ConfiguredBiasIsRemoved) {
  DeadReckoning uncorrected = Make();
  const Se2 drifted = Feed(uncorrected, BiasedDrive(0.0, 10.0)).local_T_vehicle;
  DeadReckoningOptions options;
  options.yaw_rate_bias_radps = 0.02;
  DeadReckoning corrected = Make(options);
  const Se2 pose = Feed(corrected, BiasedDrive(0.0, 10.0)).local_T_vehicle;
  const Se2 truth = ClosedFormArc(kV, kW, 10.0);
  std::printf("  heading error without / with the bias option: %.4f / %.3g rad\n",
              testing::HeadingError(drifted, truth), testing::HeadingError(pose, truth));
  EXPECT_NEAR(testing::HeadingError(drifted, truth), 0.2, 1e-9);
  EXPECT_LT(testing::PositionError(pose, truth), 1e-6);
}

TEST(DeadReckoningBias, StandingStillHoldsThePoseAndEstimatesTheBias) {
  DeadReckoningOptions options;
  options.estimate_yaw_rate_bias = true;
  options.input_hold = InputHold::kZeroOrder;  // the drive starts exactly at 5 s
  DeadReckoning odometry = Make(options);
  const std::vector<OdometryMeasurement> drive = BiasedDrive(5.0, 10.0);
  for (const OdometryMeasurement& m : drive) {
    odometry.Update(m);
    if (m.time_ns == 5 * kNsPerSecond - kPeriod) {  // parked 5 s with a biased gyro
      EXPECT_EQ(odometry.latest().local_T_vehicle.Vector(), Eigen::Vector3d::Zero());
      EXPECT_EQ(odometry.latest().covariance, Eigen::Matrix3d::Zero());
    }
  }
  std::printf("  estimated bias %.9f rad/s from %llu samples\n", odometry.yaw_rate_bias_radps(),
              static_cast<unsigned long long>(odometry.stats().bias_updates));
  EXPECT_NEAR(odometry.yaw_rate_bias_radps(), 0.02, 1e-12);
  EXPECT_EQ(odometry.stats().bias_updates, 450u);  // 4.5 s after the 0.5 s settling time
  EXPECT_LT(testing::PositionError(odometry.latest().local_T_vehicle, ClosedFormArc(kV, kW, 10.0)),
            1e-6);
}

TEST(DeadReckoningBias, NoisyStandstillEstimateIsWithinItsStandardError) {
  constexpr unsigned kSeed = 7;
  std::printf("  seed %u\n", kSeed);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 0.01);  // rad/s per 100 Hz sample
  DeadReckoningOptions options;
  options.estimate_yaw_rate_bias = true;
  DeadReckoning odometry = Make(options);
  for (OdometryMeasurement m : BiasedDrive(30.0, 0.0)) {
    *m.yaw_rate_radps += noise(rng);
    odometry.Update(m);
  }
  const double standard_error = 0.01 / std::sqrt(2950.0);  // mean of 29.5 s of samples
  std::printf("  bias %.6f rad/s, truth 0.02, standard error %.2g\n",
              odometry.yaw_rate_bias_radps(), standard_error);
  EXPECT_NEAR(odometry.yaw_rate_bias_radps(), 0.02, 4.0 * standard_error);
}

}  // namespace
}  // namespace flat2d::localization
