// Dead reckoning against closed-form poses of synthetic drives (constant speed and yaw
// rate per segment, x = v/w sin(wt), y = v/w (1 - cos(wt))). Exact arc integration makes
// the only error floating-point rounding, so the tolerance is 1e-6 m after 100+ m (the
// requirement is 1 mm); every test prints what it measured.
#include "localization/odometry/dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <vector>

#include "tests/localization/odometry/synthetic_drive.hpp"

namespace flat2d::localization {
namespace {

using testing::ClosedFormPose;
using testing::Segment;
using testing::Sensors;

constexpr double kPositionTolerance = 1e-6;  // metres
constexpr double kHeadingTolerance = 1e-9;   // radians

struct Errors {
  double position = 0.0;  // largest over all samples
  double heading = 0.0;
  double distance = 0.0;  // path length of the drive
  Se2 final_pose;
};

Errors DriveAndCompare(const std::vector<Segment>& segments, double rate_hz, const Sensors& sensors,
                       const DeadReckoningOptions& options = {}) {
  auto odometry = DeadReckoning::Create(options);
  EXPECT_TRUE(odometry.ok());
  Errors errors;
  for (const Segment& segment : segments)
    errors.distance += std::abs(segment.v_mps) * segment.duration_s;
  for (const auto& m : testing::SampleDrive(segments, rate_hz, sensors)) {
    const DeadReckoningUpdate update = odometry->Update(m);
    EXPECT_TRUE(update.new_sample());
    const Se2 expected = ClosedFormPose(segments, testing::Seconds(m.time_ns));
    errors.position =
        std::max(errors.position, testing::PositionError(update.sample.local_T_vehicle, expected));
    errors.heading =
        std::max(errors.heading, testing::HeadingError(update.sample.local_T_vehicle, expected));
    errors.final_pose = update.sample.local_T_vehicle;
  }
  std::printf("  %.0f Hz, %.1f m: max position error %.3g m, max heading error %.3g rad\n", rate_hz,
              errors.distance, errors.position, errors.heading);
  return errors;
}

void ExpectExact(const Errors& errors) {
  EXPECT_LT(errors.position, kPositionTolerance);
  EXPECT_LT(errors.heading, kHeadingTolerance);
}

TEST(DeadReckoning, FirstMeasurementIsTheOriginOfTheLocalFrame) {
  auto odometry = DeadReckoning::Create({});
  ASSERT_TRUE(odometry.ok());
  const DeadReckoningUpdate update = odometry->Update(testing::MeasurementFor(123, 5.0, 0.1, {}));
  EXPECT_EQ(update.status, UpdateStatus::kInitialized);
  EXPECT_EQ(update.sample.time_ns, 123);
  EXPECT_EQ(update.sample.local_T_vehicle.Vector(), Eigen::Vector3d::Zero());
  EXPECT_EQ(update.sample.covariance, Eigen::Matrix3d::Zero());
}

TEST(DeadReckoning, StraightLineOf100Metres) {
  for (double rate : {50.0, 100.0}) {
    const Errors errors = DriveAndCompare({{10.0, 0.0, 10.0}}, rate, {});
    ExpectExact(errors);
    EXPECT_NEAR(errors.final_pose.x(), 100.0, kPositionTolerance);
  }
}

TEST(DeadReckoning, ConstantArcWithYawRateSensor) {
  for (double rate : {50.0, 100.0}) ExpectExact(DriveAndCompare({{10.0, 0.2, 12.0}}, rate, {}));
}

TEST(DeadReckoning, ConstantArcFromRearWheelSpeedDifferenceOnly) {
  for (double rate : {50.0, 100.0}) {
    ExpectExact(DriveAndCompare({{10.0, -0.25, 12.0}}, rate, {.wheels = true, .yaw_rate = false}));
  }
}

TEST(DeadReckoning, ConstantArcFromAllFourWheelsProjectsTheSteeredFrontWheels) {
  DeadReckoningOptions options;
  options.speed_wheels = SpeedWheels::kAll;
  for (bool yaw_rate : {true, false}) {
    ExpectExact(DriveAndCompare({{8.0, 0.3, 12.0}}, 100.0, {.wheels = true, .yaw_rate = yaw_rate},
                                options));
  }
  // Why D3: the plain mean of the four wheel speeds reads 0.26 % fast on this arc.
  const hal::can::WheelSpeeds wheels = testing::WheelSpeedsFor(8.0, 0.3, {});
  const double plain_mean = 0.25 * (wheels.front_left_mps + wheels.front_right_mps +
                                    wheels.rear_left_mps + wheels.rear_right_mps);
  std::printf("  plain mean of four wheels: %+.3f %%\n", (plain_mean / 8.0 - 1.0) * 100.0);
  EXPECT_GT(plain_mean / 8.0 - 1.0, 0.002);
}

TEST(DeadReckoning, VehicleSpeedAndYawRateWithoutWheelSpeeds) {
  ExpectExact(DriveAndCompare({{12.0, 0.1, 10.0}}, 50.0,
                              {.wheels = false, .yaw_rate = true, .vehicle_speed = true}));
}

// A figure eight (a left and a right circle of 30 s) and a sequence of arcs with straights
// and reversing. Inputs change at sample times, which zero-order hold follows exactly.
TEST(DeadReckoning, FigureEightAndSequenceOfArcs) {
  const double w = 2.0 * std::numbers::pi / 30.0;
  const std::vector<Segment> figure_eight = {{5.0, w, 30.0}, {5.0, -w, 30.0}};
  const std::vector<Segment> arcs = {{10.0, 0.0, 10.0}, {8.0, 0.3, 5.0},  {8.0, 0.0, 3.0},
                                     {6.0, -0.15, 8.0}, {-2.0, 0.1, 2.0}, {15.0, 0.02, 6.0}};
  DeadReckoningOptions options;
  options.input_hold = InputHold::kZeroOrder;
  for (double rate : {50.0, 100.0}) {
    for (const Sensors sensors : {Sensors{}, Sensors{.wheels = true, .yaw_rate = false}}) {
      const Errors eight = DriveAndCompare(figure_eight, rate, sensors, options);
      ExpectExact(eight);
      EXPECT_LT(eight.final_pose.translation().norm(), kPositionTolerance);  // back home
      ExpectExact(DriveAndCompare(arcs, rate, sensors, options));
    }
  }
}

// Wheel speeds at 50 Hz and the yaw rate at 100 Hz in separate frames, offset by 3 ms:
// each step uses the newest value of each.
TEST(DeadReckoning, InputsFromSeparateFramesAtDifferentRates) {
  const double v = 10.0;
  const double w = 0.2;
  auto odometry = DeadReckoning::Create({});
  ASSERT_TRUE(odometry.ok());
  double worst = 0.0;
  for (TimeNs t = 0; t <= 10 * kNsPerSecond; t += 10 * kNsPerMs) {
    if (t % (20 * kNsPerMs) == 0) {
      odometry->Update(testing::MeasurementFor(t, v, w, {.wheels = true, .yaw_rate = false}));
    }
    const auto update = odometry->Update(
        testing::MeasurementFor(t + 3 * kNsPerMs, v, w, {.wheels = false, .yaw_rate = true}));
    worst =
        std::max(worst, testing::PositionError(
                            update.sample.local_T_vehicle,
                            testing::ClosedFormArc(v, w, testing::Seconds(update.sample.time_ns))));
  }
  std::printf("  max position error %.3g m\n", worst);
  EXPECT_LT(worst, kPositionTolerance);
  EXPECT_EQ(odometry->stats().wheel_yaw_rate_steps, 1u);  // before the first yaw-rate frame
}

// D5: with a yaw rate ramp w = a t the midpoint hold integrates the heading a t^2 / 2
// exactly (trapezoid rule); zero-order hold lags by a dt T / 2.
TEST(DeadReckoning, MidpointHoldIsExactForLinearInputsZeroOrderHoldLags) {
  const double a = 0.05;
  for (InputHold hold : {InputHold::kMidpoint, InputHold::kZeroOrder}) {
    DeadReckoningOptions options;
    options.input_hold = hold;
    auto odometry = DeadReckoning::Create(options);
    ASSERT_TRUE(odometry.ok());
    for (TimeNs t = 0; t <= 10 * kNsPerSecond; t += 10 * kNsPerMs) {
      odometry->Update(testing::MeasurementFor(t, 10.0, a * testing::Seconds(t), {}));
    }
    const double error = odometry->latest().local_T_vehicle.theta() - a * 100.0 / 2.0;
    std::printf("  %s hold: heading error %.3g rad\n",
                hold == InputHold::kMidpoint ? "midpoint" : "zero-order", error);
    if (hold == InputHold::kMidpoint) {
      EXPECT_LT(std::abs(error), 1e-12);
    } else {
      EXPECT_NEAR(error, -a * 0.01 * 10.0 / 2.0, 1e-9);
    }
  }
}

TEST(DeadReckoning, WheelSpeedScaleCalibratesTyreRadius) {
  DeadReckoningOptions options;
  options.wheel_speed_scale = 1.02;  // the tyres are 2 % larger than the CAN scaling assumes
  auto odometry = DeadReckoning::Create(options);
  ASSERT_TRUE(odometry.ok());
  for (auto m :
       testing::SampleDrive({{10.0, 0.1, 10.0}}, 100.0, {.wheels = true, .yaw_rate = false})) {
    for (double* speed : {&m.wheel_speeds->front_left_mps, &m.wheel_speeds->front_right_mps,
                          &m.wheel_speeds->rear_left_mps, &m.wheel_speeds->rear_right_mps}) {
      *speed /= 1.02;  // what the CAN bus reports
    }
    odometry->Update(m);
  }
  const Se2 expected = testing::ClosedFormArc(10.0, 0.1, 10.0);
  const double error = testing::PositionError(odometry->latest().local_T_vehicle, expected);
  std::printf("  position error after 100 m: %.3g m\n", error);
  EXPECT_LT(error, kPositionTolerance);
}

TEST(DeadReckoningOptions, ValidationNamesTheField) {
  DeadReckoningOptions options;
  EXPECT_TRUE(ValidateOptions(options).ok());
  options.track_m = 0.0;
  const Status status = ValidateOptions(options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("track_m"), std::string::npos) << status.error().message;
  options = {};
  options.yaw_rate_noise_rad_per_sqrt_s = std::nan("");
  EXPECT_FALSE(DeadReckoning::Create(options).ok());
  options = {};
  options.max_gap_ns = 0;
  EXPECT_FALSE(ValidateOptions(options).ok());
}

}  // namespace
}  // namespace flat2d::localization
