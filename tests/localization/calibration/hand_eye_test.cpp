#include "localization/calibration/hand_eye.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"

namespace flat2d::localization::calibration {
namespace {

Eigen::Isometry3d Pose(double x, double y, double z, double roll_deg, double pitch_deg, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  pose.linear() = (Eigen::AngleAxisd(yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

// A mounting 0.8 m ahead, 0.3 m right, 1.6 m up, rolled, pitched and turned 30 deg.
const Eigen::Isometry3d kTruth = Pose(0.8, -0.3, 1.6, 2.0, -3.0, 30.0);
// ... and the guess the solver starts from: 0.2 m and 5 deg off on every component.
const Eigen::Isometry3d kGuess = Pose(1.0, -0.1, 1.8, 7.0, -8.0, 35.0);

// A vehicle at 10 Hz and 3 m/s: straight, left turns and right turns of 10 m radius, and
// when `hilly` rolling and pitching a few degrees as over ramps and cambers.
std::vector<Eigen::Isometry3d> VehiclePath(bool turns, bool hilly) {
  std::vector<Eigen::Isometry3d> path;
  double x = 0.0, y = 0.0, heading = 0.0;
  for (int i = 0; i < 600; ++i) {
    const double t = 0.1 * i;
    const double yaw_rate = turns ? 0.3 * std::sin(2.0 * std::numbers::pi * t / 20.0) : 0.0;
    heading += yaw_rate * 0.1;
    x += 0.3 * std::cos(heading);
    y += 0.3 * std::sin(heading);
    const double roll = hilly ? 3.0 * std::sin(t / 3.0) : 0.0;
    const double pitch = hilly ? 4.0 * std::sin(t / 5.0) : 0.0;
    const double z = hilly ? 0.5 * std::sin(t / 4.0) : 0.0;
    path.push_back(Pose(x, y, z, roll, pitch, heading / kDegToRad));
  }
  return path;
}

// The sensor's track seen through the mounting, each pose off by a tracker's few mm and
// hundredths of a degree.
std::vector<Eigen::Isometry3d> SensorTrack(const std::vector<Eigen::Isometry3d>& vehicle, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> millimetres(0.0, 0.003), degrees(0.0, 0.02);
  std::vector<Eigen::Isometry3d> track;
  for (const Eigen::Isometry3d& pose : vehicle) {
    // Drawn in order first: as arguments of one call the draws would have no order.
    const double x = millimetres(random), y = millimetres(random), z = millimetres(random);
    const double roll = degrees(random), pitch = degrees(random), yaw = degrees(random);
    const Eigen::Isometry3d noise = Pose(x, y, z, roll, pitch, yaw);
    track.push_back(pose * kTruth * noise);
  }
  return track;
}

// height_metres 0: the height is not judged.
void ExpectNear(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth, double metres, double degrees,
                double height_metres) {
  const Eigen::Vector3d d = estimate.translation() - truth.translation();
  EXPECT_LT(d.head<2>().norm(), metres) << d.transpose();
  if (height_metres > 0.0) {
    EXPECT_LT(std::abs(d.z()), height_metres) << d.transpose();
  }
  EXPECT_LT(Eigen::AngleAxisd(estimate.rotation().transpose() * truth.rotation()).angle(), degrees * kDegToRad);
}

TEST(HandEye, PlanarDriveRecoversAllButTheHeight) {
  const auto vehicle = VehiclePath(true, false);
  const auto pairs = MotionPairs(SensorTrack(vehicle, 1), vehicle);
  ASSERT_GT(pairs.size(), 100U);
  auto result = SolveHandEye(pairs, kGuess);
  ASSERT_TRUE(result.ok()) << result.error().message;
  ExpectNear(result->vehicle_T_sensor, kTruth, 0.01, 0.05, 0.0);
  // The height is not observable on a plane: it stays where the guess put it.
  EXPECT_NEAR(result->vehicle_T_sensor.translation().z(), kGuess.translation().z(), 1e-9);
  const std::array<bool, 6> expected{true, true, false, true, true, true};
  EXPECT_EQ(result->observable, expected);
  EXPECT_EQ(result->sigma[2], 0.0);
  EXPECT_GT(result->sigma[0], 0.0);
  EXPECT_LT(result->sigma[0], 0.01);
  EXPECT_EQ(result->inliers, result->pairs);
  EXPECT_LT(result->rms_translation_m, 0.01);
}

TEST(HandEye, RollingAndPitchingMakesTheHeightObservable) {
  const auto vehicle = VehiclePath(true, true);
  auto result = SolveHandEye(MotionPairs(SensorTrack(vehicle, 2), vehicle), kGuess);
  ASSERT_TRUE(result.ok()) << result.error().message;
  // Rolls of 3 deg see the height only weakly: over the tracker noise of seeds 1-100 its
  // error was 3.2 mm median, 6.7 mm p90 and 10.6 mm at most (the solver's own sigma: 2 cm).
  ExpectNear(result->vehicle_T_sensor, kTruth, 0.01, 0.05, 0.015);
  for (bool observable : result->observable) EXPECT_TRUE(observable);
}

TEST(HandEye, StraightDriveConstrainsOnlyTheDirectionOfTravel) {
  // Pure translation: the sensor sees the vehicle's x axis, which fixes pitch and yaw, and
  // nothing else (roll turns about that axis; no rotation, no lever arm).
  const auto vehicle = VehiclePath(false, false);
  auto result = SolveHandEye(MotionPairs(SensorTrack(vehicle, 3), vehicle), kGuess);
  ASSERT_TRUE(result.ok()) << result.error().message;
  const std::array<bool, 6> expected{false, false, false, false, true, true};
  EXPECT_EQ(result->observable, expected);
  EXPECT_EQ(result->vehicle_T_sensor.translation(), kGuess.translation());
}

TEST(HandEye, NearlyStraightDriveHoldsTheLeverArm) {
  // A straight drive whose heading wanders by hundredths of a degree (a gyro's noise): the
  // lever arm gets a little information, far too little to trust, and stays at the guess.
  auto vehicle = VehiclePath(false, false);
  std::mt19937 random(9);
  std::normal_distribution<double> wander(0.0, 0.03);
  for (Eigen::Isometry3d& pose : vehicle) pose = pose * Pose(0.0, 0.0, 0.0, 0.0, 0.0, wander(random));
  auto result = SolveHandEye(MotionPairs(SensorTrack(vehicle, 6), vehicle), kGuess);
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_FALSE(result->observable[0]);
  EXPECT_FALSE(result->observable[1]);
  EXPECT_EQ(result->vehicle_T_sensor.translation(), kGuess.translation());
  EXPECT_TRUE(result->observable[4]);
  EXPECT_TRUE(result->observable[5]);
  // The direction of travel in the sensor frame is what it does know.
  const Eigen::Vector3d travel = result->vehicle_T_sensor.rotation().transpose() * Eigen::Vector3d::UnitX();
  EXPECT_LT(std::acos(std::min(1.0, travel.dot(kTruth.rotation().transpose() * Eigen::Vector3d::UnitX()))), 0.05 * kDegToRad);
}

TEST(HandEye, WrongSensorMotionsAreDownWeighted) {
  const auto vehicle = VehiclePath(true, false);
  auto pairs = MotionPairs(SensorTrack(vehicle, 4), vehicle);
  // One pair in ten a failed registration: 1 m and 10 deg off.
  for (std::size_t i = 0; i < pairs.size(); i += 10) pairs[i].sensor_motion = pairs[i].sensor_motion * Pose(1.0, 0.0, 0.0, 0.0, 0.0, 10.0);
  auto result = SolveHandEye(pairs, kGuess);
  ASSERT_TRUE(result.ok()) << result.error().message;
  ExpectNear(result->vehicle_T_sensor, kTruth, 0.02, 0.1, 0.0);
  EXPECT_LE(result->inliers, result->pairs - static_cast<int>(pairs.size() / 10));
}

TEST(HandEye, WheelScaleErrorIsNotALeverArm) {
  // Wheels that measure 0.5 % long: taken as they are, the lever arm soaks the error up
  // across the turns (0.5 % of the 10 m radius); scaled to the sensor's distances first, not.
  // Left turns only, as round a block: 10 s straight, then 5 s at 0.3 rad/s (10 m radius).
  std::vector<Eigen::Isometry3d> vehicle;
  double x = 0.0, y = 0.0, heading = 0.0;
  for (int i = 0; i < 600; ++i) {
    heading += (i % 150 >= 100 ? 0.3 : 0.0) * 0.1;
    x += 0.3 * std::cos(heading);
    y += 0.3 * std::sin(heading);
    vehicle.push_back(Pose(x, y, 0.0, 0.0, 0.0, heading / kDegToRad));
  }
  auto pairs = MotionPairs(SensorTrack(vehicle, 8), vehicle);
  for (MotionPair& pair : pairs) pair.vehicle_motion.translation() *= 1.005;
  auto raw = SolveHandEye(pairs, kGuess);
  ASSERT_TRUE(raw.ok()) << raw.error().message;
  EXPECT_GT((raw->vehicle_T_sensor.translation() - kTruth.translation()).head<2>().norm(), 0.03);
  const double scale = OdometryDistanceScale(pairs);
  EXPECT_NEAR(scale, 1.0 / 1.005, 2e-4);
  for (MotionPair& pair : pairs) pair.vehicle_motion.translation() *= scale;
  auto scaled = SolveHandEye(pairs, kGuess);
  ASSERT_TRUE(scaled.ok()) << scaled.error().message;
  ExpectNear(scaled->vehicle_T_sensor, kTruth, 0.01, 0.05, 0.0);
  EXPECT_EQ(OdometryDistanceScale({}), 1.0);
}

TEST(HandEye, MotionPairsSpanTheGivenDistance) {
  const auto vehicle = VehiclePath(false, false);  // 0.3 m per step
  const auto pairs = MotionPairs(vehicle, vehicle, 1.0, 0.1);
  ASSERT_EQ(pairs.size(), vehicle.size() - 4);
  for (const MotionPair& pair : pairs) EXPECT_NEAR(pair.vehicle_motion.translation().norm(), 1.2, 1e-9);
}

TEST(HandEye, BadInputIsAnError) {
  const auto vehicle = VehiclePath(true, false);
  auto pairs = MotionPairs(SensorTrack(vehicle, 5), vehicle);
  auto few = SolveHandEye(std::span(pairs).first(5), kGuess);
  ASSERT_FALSE(few.ok());
  EXPECT_NE(few.error().message.find("fewer than"), std::string::npos);
  pairs[7].sensor_motion.translation().x() = std::nan("");
  auto nan = SolveHandEye(pairs, kGuess);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().message.find("pair 7"), std::string::npos);
  // A tracker that lost its way: the sensor's motions have nothing to do with the vehicle's.
  auto lost = MotionPairs(SensorTrack(vehicle, 5), vehicle);
  for (std::size_t i = 0; i < lost.size(); ++i) lost[i].sensor_motion = Pose(0.5 * std::sin(i * 0.7), 0.3, 0.0, 0.0, 0.0, 20.0 * std::cos(i * 1.3));
  auto disagree = SolveHandEye(lost, kGuess);
  ASSERT_FALSE(disagree.ok());
  EXPECT_NE(disagree.error().message.find("did the tracking fail"), std::string::npos);
  std::vector<MotionPair> standing(50);
  auto still = SolveHandEye(standing, kGuess);
  ASSERT_FALSE(still.ok());
  EXPECT_NE(still.error().message.find("constrain no component"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::localization::calibration
