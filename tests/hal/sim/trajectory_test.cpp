// Vehicle motion along a drive: the path, the speed profile within its limits, the body on
// the ground, and the sensor quantities (yaw rate, wheel speeds, steering), each checked by
// numerical differentiation of the poses or by geometry worked out by hand.
#include "hal/sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kPi = std::numbers::pi;

Drive MakeDrive(const std::vector<Eigen::Vector2d>& waypoints, double speed, double radius,
                bool loop = false) {
  Drive drive;
  drive.set_name("test-drive");
  for (const Eigen::Vector2d& p : waypoints) {
    Vec2* w = drive.add_waypoints();
    w->set_x(p.x());
    w->set_y(p.y());
  }
  drive.set_speed_mps(speed);
  drive.set_corner_radius_m(radius);
  drive.set_loop(loop);
  return drive;
}

double Flat(double, double) { return 0.0; }

Trajectory Make(const Drive& drive, const GroundHeightFn& ground = Flat) {
  auto trajectory = Trajectory::Create(ground, drive);
  EXPECT_TRUE(trajectory.ok()) << (trajectory.ok() ? "" : trajectory.error().message);
  return std::move(trajectory).value();
}

Eigen::Vector3d Position(const VehicleState& state) { return state.world_T_vehicle.translation(); }
double Yaw(const VehicleState& s) {
  return std::atan2(s.world_T_vehicle.linear()(1, 0), s.world_T_vehicle.linear()(0, 0));
}
double Pitch(const VehicleState& s) { return std::asin(s.world_T_vehicle.linear()(2, 0)); }
double Roll(const VehicleState& s) {
  return std::atan2(s.world_T_vehicle.linear()(2, 1), s.world_T_vehicle.linear()(2, 2));
}
double AngleDiff(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

// A drive with left and right corners of two radii-worth of room, fast enough that the
// lateral limit binds in the corners.
Drive Zigzag() {
  return MakeDrive({{0, 0}, {150, 0}, {150, 40}, {190, 40}, {190, 0}, {340, 0}}, 10.0, 8.0);
}

TEST(TrajectoryTest, PathIsTheRoundedPolyline) {
  const Trajectory trajectory = Make(MakeDrive({{0, 0}, {20, 0}, {20, 20}}, 2.0, 5.0));
  // Two straights of 15 m and a quarter circle of radius 5.
  EXPECT_NEAR(trajectory.path_length_m(), 30.0 + 2.5 * kPi, 1e-9);
  int on_arc = 0;
  for (double t = 0.0; t <= trajectory.duration_s(); t += 0.01) {
    const VehicleState state = trajectory.At(t);
    const double yaw = Yaw(state);
    if (yaw > 1e-6 && yaw < kPi / 2 - 1e-6) {
      ++on_arc;
      EXPECT_NEAR((Position(state).head<2>() - Eigen::Vector2d(15, 5)).norm(), 5.0, 1e-9);
      EXPECT_NEAR(state.steering_angle_rad, std::atan(trajectory.geometry().wheelbase_m / 5.0), 1e-12);
    }
  }
  EXPECT_GT(on_arc, 100);
  EXPECT_NEAR((Position(trajectory.At(trajectory.duration_s())).head<2>() -
               Eigen::Vector2d(20, 20)).norm(), 0.0, 1e-9);
}

TEST(TrajectoryTest, DurationMatchesConstantAccelerationByHand) {
  // 200 m at 10 m/s with 1 m/s^2: 10 s up (50 m), 10 s cruising (100 m), 10 s down (50 m).
  const Trajectory trajectory = Make(MakeDrive({{0, 0}, {200, 0}}, 10.0, 0.0));
  EXPECT_NEAR(trajectory.duration_s(), 30.0, 1e-6);
  EXPECT_NEAR(trajectory.At(5.0).speed_mps, 5.0, 1e-6);
  EXPECT_NEAR(Position(trajectory.At(5.0)).x(), 12.5, 1e-6);
  EXPECT_NEAR(Position(trajectory.At(15.0)).x(), 100.0, 1e-6);
  EXPECT_NEAR(trajectory.At(25.0).speed_mps, 5.0, 1e-6);
}

TEST(TrajectoryTest, PositionIsContinuousAndSpeedWithinLimits) {
  const Drive drive = Zigzag();
  const Trajectory trajectory = Make(drive);
  constexpr double kDt = 0.001;
  Eigen::Vector3d previous = Position(trajectory.At(0.0));
  double top_speed = 0.0;
  for (double t = kDt; t <= trajectory.duration_s() + 1.0; t += kDt) {
    const VehicleState state = trajectory.At(t);
    EXPECT_GE(state.speed_mps, 0.0);
    EXPECT_LE(state.speed_mps, drive.speed_mps() + 1e-9);
    // No jump: the step is at most what the top speed covers in dt.
    ASSERT_LE((Position(state) - previous).norm(), drive.speed_mps() * kDt + 1e-9) << "t=" << t;
    previous = Position(state);
    top_speed = std::max(top_speed, state.speed_mps);
  }
  EXPECT_NEAR(top_speed, drive.speed_mps(), 1e-6);
  EXPECT_EQ(trajectory.At(0.0).speed_mps, 0.0);
  EXPECT_NEAR(trajectory.At(trajectory.duration_s()).speed_mps, 0.0, 1e-9);
  EXPECT_NEAR((Position(trajectory.At(1e9)).head<2>() - Eigen::Vector2d(340, 0)).norm(), 0, 1e-9);
}

TEST(TrajectoryTest, AccelerationAndLateralAccelerationWithinLimits) {
  const Trajectory trajectory = Make(Zigzag());  // defaults: 1.0 and 2.0 m/s^2
  constexpr double kH = 0.01;
  double max_lateral = 0.0;
  for (double t = kH; t <= trajectory.duration_s() - kH; t += 0.005) {
    const VehicleState before = trajectory.At(t - kH), now = trajectory.At(t),
                       after = trajectory.At(t + kH);
    // Speed is piecewise linear in time with slopes within the limit: exact up to rounding.
    EXPECT_LE(std::abs(after.speed_mps - now.speed_mps) / kH, 1.0 + 1e-6) << "t=" << t;
    // Lateral: the second difference of position across the heading (a 20 ms window
    // smears the steps where an arc meets a straight, never beyond the limit).
    const Eigen::Vector2d accel =
        (Position(after) - 2.0 * Position(now) + Position(before)).head<2>() / (kH * kH);
    const Eigen::Vector2d left(-std::sin(Yaw(now)), std::cos(Yaw(now)));
    const double lateral = std::abs(accel.dot(left));
    EXPECT_LE(lateral, 2.0 * 1.01) << "t=" << t;
    EXPECT_LE(now.speed_mps * std::abs(now.yaw_rate_radps), 2.0 + 1e-9) << "t=" << t;
    max_lateral = std::max(max_lateral, lateral);
  }
  // The corners (radius 8 m) are taken at the limit: sqrt(2 * 8) = 4 m/s, not 10.
  EXPECT_NEAR(max_lateral, 2.0, 0.02);
}

TEST(TrajectoryTest, HeadingIsPathTangentAndYawRateItsDerivative) {
  const Trajectory trajectory = Make(Zigzag());
  constexpr double kH = 0.002;
  double integrated_yaw = 0.0;
  double previous_rate = trajectory.At(0.0).yaw_rate_radps;
  double previous_yaw = Yaw(trajectory.At(0.0));
  double unwrapped_yaw = previous_yaw;
  int compared = 0;
  for (double t = kH; t <= trajectory.duration_s() - kH; t += kH) {
    const VehicleState before = trajectory.At(t - kH), now = trajectory.At(t),
                       after = trajectory.At(t + kH);
    if (now.speed_mps > 0.1) {
      const Eigen::Vector3d velocity = Position(trajectory.At(t + 1e-5)) - Position(trajectory.At(t - 1e-5));
      EXPECT_NEAR(AngleDiff(Yaw(now), std::atan2(velocity.y(), velocity.x())), 0.0, 1e-4)
          << "t=" << t;
    }
    // Pointwise where the yaw rate does not step inside the window.
    if (std::abs(after.yaw_rate_radps - before.yaw_rate_radps) < 1e-3) {
      EXPECT_NEAR(AngleDiff(Yaw(after), Yaw(before)) / (2 * kH), now.yaw_rate_radps, 1e-4);
      ++compared;
    }
    integrated_yaw += 0.5 * (previous_rate + now.yaw_rate_radps) * kH;
    previous_rate = now.yaw_rate_radps;
    unwrapped_yaw += AngleDiff(Yaw(now), previous_yaw);
    previous_yaw = Yaw(now);
  }
  EXPECT_GT(compared, 1000);
  EXPECT_NEAR(integrated_yaw, unwrapped_yaw, 2e-3);
}

TEST(TrajectoryTest, WheelSpeedsMatchTheirGroundTracks) {
  const Trajectory trajectory = Make(Zigzag());
  const VehicleGeometry& g = trajectory.geometry();
  const Eigen::Vector3d wheels[4] = {{g.wheelbase_m, g.track_m / 2, 0}, {g.wheelbase_m, -g.track_m / 2, 0},
                                     {0, g.track_m / 2, 0}, {0, -g.track_m / 2, 0}};
  // A short window: where the acceleration steps, the central difference is off by a*h/2.
  constexpr double kH = 1e-4;
  int arcs = 0;
  for (double t = kH; t <= trajectory.duration_s() - kH; t += 0.01) {
    const VehicleState before = trajectory.At(t - kH), now = trajectory.At(t),
                       after = trajectory.At(t + kH);
    const auto& w = now.wheel_speeds_mps;
    EXPECT_NEAR(0.5 * (w[kRearLeft] + w[kRearRight]), now.speed_mps, 1e-9);
    EXPECT_NEAR(w[kRearRight] - w[kRearLeft], now.yaw_rate_radps * g.track_m, 1e-9);
    if (std::abs(after.yaw_rate_radps - before.yaw_rate_radps) > 1e-3) continue;
    // Each wheel's speed is how fast its contact point moves (numerically).
    for (int i = 0; i < 4; ++i) {
      const double track_speed =
          (after.world_T_vehicle * wheels[i] - before.world_T_vehicle * wheels[i]).norm() / (2 * kH);
      EXPECT_NEAR(w[i], track_speed, 1e-4) << "wheel " << i << " t=" << t;
    }
    // On an arc the front wheels are sqrt(L^2 + (R -+ t/2)^2) from the turning centre.
    if (std::abs(now.yaw_rate_radps) > 1e-3) {
      ++arcs;
      const double radius = now.speed_mps / now.yaw_rate_radps;  // signed, left positive
      EXPECT_NEAR(w[kFrontLeft], std::abs(now.yaw_rate_radps) *
                                     std::hypot(g.wheelbase_m, radius - g.track_m / 2), 1e-9);
      EXPECT_NEAR(w[kFrontRight], std::abs(now.yaw_rate_radps) *
                                      std::hypot(g.wheelbase_m, radius + g.track_m / 2), 1e-9);
    }
  }
  EXPECT_GT(arcs, 100);
}

TEST(TrajectoryTest, BodyFollowsARampAndACrossSlope) {
  const double slope = 10.0 * kPi / 180.0;
  // Up a 10 degree incline from x = 10 to x = 30, level after.
  auto ramp = [slope](double x, double) { return std::clamp(x - 10.0, 0.0, 20.0) * std::tan(slope); };
  const Trajectory trajectory = Make(MakeDrive({{0, 0}, {50, 0}}, 3.0, 0.0), ramp);
  const double wheelbase = trajectory.geometry().wheelbase_m;
  int on_ramp = 0;
  for (double t = 0.01; t < trajectory.duration_s() - 0.01; t += 0.01) {
    const VehicleState state = trajectory.At(t);
    const Eigen::Vector3d p = Position(state);
    EXPECT_NEAR(p.z(), ramp(p.x(), p.y()), 1e-2);
    if (p.x() > 10.1 && p.x() + wheelbase < 29.9) {
      ++on_ramp;
      EXPECT_NEAR(Pitch(state), slope, 0.5 * kPi / 180.0) << "x=" << p.x();
      const double along = (Position(trajectory.At(t + 1e-3)) - Position(trajectory.At(t - 1e-3))).norm();
      EXPECT_NEAR(state.speed_mps, along / 2e-3, 1e-3);  // along the slope, not horizontal
    }
    if (p.x() > 30.1 || p.x() + wheelbase < 9.9) {
      EXPECT_NEAR(Pitch(state), 0.0, 1e-9);
    }
  }
  EXPECT_GT(on_ramp, 100);

  // Ground rising to the left (+y) tilts the body left side up.
  const Trajectory tilted = Make(MakeDrive({{0, 0}, {30, 0}}, 3.0, 0.0),
                                 [](double, double y) { return 0.1 * y; });
  EXPECT_NEAR(Roll(tilted.At(5.0)), std::atan(0.1), 1e-9);
  EXPECT_NEAR(Pitch(tilted.At(5.0)), 0.0, 1e-9);
}

TEST(TrajectoryTest, FollowsASceneRamp) {
  SceneDescription description;
  Ramp* ramp = description.mutable_ground()->add_ramps();
  ramp->mutable_start()->set_x(10.0);
  ramp->set_heading(0.0);
  ramp->set_run_m(8.0);
  ramp->set_width_m(4.0);
  ramp->set_slope_deg(14.5);
  ramp->set_plateau_m(4.0);
  ramp->set_descend(true);
  auto scene = Scene::Create(description);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  auto trajectory = Trajectory::Create(*scene, MakeDrive({{0, 0}, {40, 0}}, 2.0, 0.0));
  ASSERT_TRUE(trajectory.ok()) << trajectory.error().message;
  // Rear axle past the foot, front axle before the top: the body lies on the slope.
  for (const double x : {10.5, 12.0, 14.0}) {
    double t = 0.0;
    while (Position(trajectory->At(t)).x() < x) t += 0.01;
    EXPECT_NEAR(Pitch(trajectory->At(t)) * 180.0 / kPi, 14.5, 0.5) << "x=" << x;
    EXPECT_NEAR(Position(trajectory->At(t)).z(), scene->GroundHeight(x, 0.0), 0.02);
  }
}

TEST(TrajectoryTest, LoopKeepsGoingLapAfterLap) {
  const Drive drive = MakeDrive({{0, 0}, {40, 0}, {40, 30}, {-20, 30}, {-20, 0}}, 8.0, 6.0, true);
  const Trajectory trajectory = Make(drive);
  ASSERT_TRUE(trajectory.loop());
  const double first = trajectory.duration_s(), lap = trajectory.lap_duration_s();
  ASSERT_GT(lap, 0.0);
  EXPECT_LT(lap, first);  // the first lap starts from rest
  constexpr double kDt = 0.001;
  Eigen::Vector3d previous = Position(trajectory.At(0.0));
  for (double t = kDt; t <= first + 3.0 * lap; t += kDt) {
    const VehicleState state = trajectory.At(t);
    ASSERT_LE((Position(state) - previous).norm(), drive.speed_mps() * kDt + 1e-9) << "t=" << t;
    ASSERT_GT(state.speed_mps, 0.0) << "t=" << t;
    previous = Position(state);
  }
  for (int k = 0; k < 4; ++k) {
    const VehicleState at_start = trajectory.At(first + k * lap);
    EXPECT_NEAR(Position(at_start).head<2>().norm(), 0.0, 1e-6) << "lap " << k;
    EXPECT_NEAR(AngleDiff(Yaw(at_start), 0.0), 0.0, 1e-9);
    EXPECT_NEAR(at_start.speed_mps, trajectory.At(first + (k + 1) * lap).speed_mps, 1e-6);
  }
  // Lap after lap the motion repeats.
  const VehicleState a = trajectory.At(first + 0.37 * lap), b = trajectory.At(first + 5.37 * lap);
  EXPECT_NEAR((Position(a) - Position(b)).norm(), 0.0, 1e-6);
  EXPECT_NEAR(a.speed_mps, b.speed_mps, 1e-9);
}

TEST(TrajectoryTest, AtAllocatesNothing) {
  const Trajectory trajectory = Make(Zigzag());
  double sink = 0.0;
  const auto before = testing::AllocationCount();
  for (double t = 0.0; t < trajectory.duration_s(); t += 0.003) sink += trajectory.At(t).speed_mps;
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_GT(sink, 0.0);
}

TEST(TrajectoryTest, ClampsOutsideTheDrive) {
  const Trajectory trajectory = Make(Zigzag());
  EXPECT_EQ(Position(trajectory.At(-5.0)), Position(trajectory.At(0.0)));
  EXPECT_EQ(Position(trajectory.At(trajectory.duration_s() + 100.0)),
            Position(trajectory.At(trajectory.duration_s())));
  EXPECT_EQ(trajectory.At(trajectory.duration_s() + 100.0).speed_mps, 0.0);
}

TEST(TrajectoryTest, RejectsInvalidDrives) {
  struct Case {
    const char* what;
    Drive drive;
    const char* expected;
  };
  Drive nan_point = MakeDrive({{0, 0}, {10, 0}}, 1.0, 0.0);
  nan_point.mutable_waypoints(1)->set_x(std::nan(""));
  Drive bad_accel = MakeDrive({{0, 0}, {10, 0}}, 1.0, 0.0);
  bad_accel.set_max_accel_mps2(-1.0);
  const Case cases[] = {
      {"one waypoint", MakeDrive({{0, 0}}, 1.0, 1.0), "at least 2"},
      {"zero speed", MakeDrive({{0, 0}, {10, 0}}, 0.0, 1.0), "speed_mps"},
      {"negative speed", MakeDrive({{0, 0}, {10, 0}}, -2.0, 1.0), "speed_mps"},
      {"too sharp", MakeDrive({{0, 0}, {10, 0}, {10, 3}, {20, 3}}, 1.0, 5.0), "too sharp"},
      {"u-turn", MakeDrive({{0, 0}, {10, 0}, {0, 0.01}}, 1.0, 1.0), "U-turn"},
      {"repeated", MakeDrive({{0, 0}, {10, 0}, {10, 0}, {20, 5}}, 1.0, 1.0), "same point"},
      {"no radius", MakeDrive({{0, 0}, {10, 0}, {10, 10}}, 1.0, 0.0), "corner_radius_m"},
      {"short loop", MakeDrive({{0, 0}, {10, 0}}, 1.0, 1.0, true), "at least 3"},
      {"not finite", nan_point, "not finite"},
      {"bad accel", bad_accel, "acceleration"},
  };
  for (const Case& c : cases) {
    auto trajectory = Trajectory::Create(Flat, c.drive);
    ASSERT_FALSE(trajectory.ok()) << c.what;
    EXPECT_NE(trajectory.error().message.find("drive 'test-drive'"), std::string::npos)
        << trajectory.error().message;
    EXPECT_NE(trajectory.error().message.find(c.expected), std::string::npos)
        << c.what << ": " << trajectory.error().message;
  }
}

TEST(TrajectoryTest, FootprintIsTheBodyOutline) {
  const VehicleGeometry geometry;
  const Eigen::AlignedBox2d box = VehicleFootprint(geometry);
  EXPECT_DOUBLE_EQ(box.sizes().x(), geometry.length_m);
  EXPECT_DOUBLE_EQ(box.sizes().y(), geometry.width_m);
  EXPECT_DOUBLE_EQ(box.min().x(), -geometry.rear_overhang_m);
}

}  // namespace
}  // namespace flat2d::hal::sim
