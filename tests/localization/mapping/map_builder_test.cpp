// The map builder on a simulated 2D laser world with ground truth: a corridor loop around
// a block, with pillars that break its symmetry, driven twice. Odometry is the truth
// corrupted by the noise model, so the test can tell a builder that corrects drift (loop
// closures found, trajectory back near the truth) from one that follows odometry.
#include "localization/mapping/map_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "localization/evaluation/relations.hpp"
#include "localization/evaluation/trajectory_error.hpp"

namespace flat2d::localization::mapping {
namespace {

struct Segment {
  Eigen::Vector2d a, b;
};

void AddBox(std::vector<Segment>& world, double x0, double y0, double x1, double y1) {
  const Eigen::Vector2d p[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  for (int i = 0; i < 4; ++i) world.push_back({p[i], p[(i + 1) % 4]});
}

// Outer walls 24 x 16 m, an inner block leaving a 4 m corridor, pillars along it.
std::vector<Segment> CorridorLoop() {
  std::vector<Segment> world;
  AddBox(world, 0, 0, 24, 16);
  AddBox(world, 4, 4, 20, 12);
  AddBox(world, 7.0, 0.0, 7.6, 0.8);    // pillars against the walls
  AddBox(world, 13.0, 3.3, 13.4, 4.0);
  AddBox(world, 23.0, 6.0, 24.0, 6.5);
  AddBox(world, 16.0, 15.0, 17.5, 16.0);
  AddBox(world, 9.0, 12.0, 9.5, 12.6);
  AddBox(world, 0.0, 9.0, 0.7, 9.4);
  AddBox(world, 2.8, 5.0, 3.1, 5.3);
  return world;
}

double CastRay(const std::vector<Segment>& world, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : world) {
    const Eigen::Vector2d e = s.b - s.a;
    const double denominator = direction.x() * e.y() - direction.y() * e.x();
    if (std::abs(denominator) < 1e-12) continue;
    const Eigen::Vector2d w = s.a - origin;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denominator;
    const double u = (w.x() * direction.y() - w.y() * direction.x()) / denominator;
    if (t > 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

// The path around the corridor's centre line (2 m from the outer walls), a pose every
// 0.25 m, turning on the spot at the corners.
std::vector<Se2> TwoLaps() {
  const Eigen::Vector2d corners[4] = {{2, 2}, {22, 2}, {22, 14}, {2, 14}};
  std::vector<Se2> path;
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d from = corners[side], to = corners[(side + 1) % 4];
      const double heading = std::atan2(to.y() - from.y(), to.x() - from.x());
      const int steps = static_cast<int>((to - from).norm() / 0.25);
      for (int i = 0; i < steps; ++i) path.emplace_back(from + (to - from) * (static_cast<double>(i) / steps), heading);
      for (int k = 1; k < 4; ++k) path.emplace_back(to, heading + k * std::numbers::pi / 8);
    }
  }
  path.emplace_back(corners[0], 0.0);
  return path;
}

std::vector<Eigen::Vector2d> Scan(const std::vector<Segment>& world, const Se2& pose, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 180; ++i) {  // every 2 degrees all round
    const double bearing = (2 * i - 180) * std::numbers::pi / 180.0;
    const Eigen::Vector2d direction(std::cos(pose.theta() + bearing), std::sin(pose.theta() + bearing));
    const double range = CastRay(world, pose.translation(), direction);
    if (range > 20.0) continue;
    const double measured = range + noise(random);
    points.emplace_back(measured * std::cos(bearing), measured * std::sin(bearing));
  }
  return points;
}

// The builder fed a scan of `world` at every truth pose with its odometry pose, finished;
// the truth, the odometry and the builder's corrected poses, a pose every 0.1 s.
struct Drive {
  std::vector<evaluation::TimedPose> reference, drifted, estimate;
};

Drive DriveThrough(MapBuilder& builder, const std::vector<Segment>& world, const std::vector<Se2>& truth,
                   const std::vector<Se2>& odometry, unsigned seed) {
  std::mt19937 random(seed);
  Drive drive;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double t = 0.1 * static_cast<double>(i);
    builder.AddScan(t, odometry[i], Scan(world, truth[i], random));
    drive.reference.push_back({t, truth[i]});
    drive.drifted.push_back({t, odometry[i]});
  }
  builder.Finish();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    drive.estimate.push_back({drive.reference[i].time_s, builder.CorrectedPose(drive.reference[i].time_s, odometry[i])});
  }
  return drive;
}

TEST(MapBuilder, ClosesTheLoopAndRemovesOdometryDrift) {
  const auto world = CorridorLoop();
  const auto truth = TwoLaps();
  OdometryNoiseModel noise;
  noise.seed = 3;
  const auto odometry = CorruptOdometry(truth, noise);

  MapBuilderOptions options;
  options.odometry = noise;
  MapBuilder builder(options);
  builder.SetAnchor(truth.front());
  const auto [reference, drifted, estimate] = DriveThrough(builder, world, truth, odometry, 11);

  const MapBuilderStats& stats = builder.stats();
  EXPECT_GT(stats.keyframes, 200u);
  EXPECT_GT(stats.tracking_accepted, stats.keyframes * 9 / 10);
  EXPECT_GE(stats.loop_accepted, 10u);
  // Loops whose match agrees with the truth are kept at the solution, the others switched
  // off (the wide search far from the last loop may match the wrong corner of the block).
  std::size_t true_loops = 0;
  for (const auto& loop : builder.graph().mixture_betweens) {
    const auto index = [&](std::size_t node) {
      return static_cast<std::size_t>(std::lround(builder.keyframes()[node].time_s / 0.1));
    };
    const Se2 truth_step = truth[index(loop.from)].Inverse() * truth[index(loop.to)];
    const Se2 miss = truth_step.Inverse() * loop.measurement;
    // A loop's submap sits at its keyframes' estimates of the time, a few cm and degrees off.
    const bool is_true = miss.translation().norm() < 0.2 && std::abs(miss.theta()) < 0.06;
    const bool is_false = miss.translation().norm() > 0.5 || std::abs(miss.theta()) > 0.1;
    const Eigen::Vector3d error = graph::BetweenError(builder.graph().nodes[loop.from].estimate,
                                                      builder.graph().nodes[loop.to].estimate, loop.measurement);
    const bool kept = graph::SelectMixtureComponent(loop.mixture, error).component == 0;
    if (is_true || is_false) {
      EXPECT_EQ(kept, is_true) << "loop " << loop.from << " -> " << loop.to << " misses the truth by "
                               << miss.translation().norm() << " m, " << miss.theta() << " rad";
    }
    if (!kept) std::printf("loop %zu -> %zu switched off: misses the truth by %.3f m, %.3f rad\n", loop.from, loop.to,
                           miss.translation().norm(), miss.theta());
    true_loops += is_true ? 1 : 0;
  }
  EXPECT_GE(true_loops, 10u);

  const auto odometry_error = evaluation::EvaluateTrajectory(drifted, reference, /*align=*/false);
  const auto error = evaluation::EvaluateTrajectory(estimate, reference, /*align=*/false);
  std::printf("odometry ATE rmse %.3f m; builder ATE rmse %.3f m, max %.3f m; odometry scale %.4f\n",
              odometry_error.rmse_m, error.rmse_m, error.max_m, stats.odometry_scale);
  EXPECT_GT(odometry_error.rmse_m, 0.3) << "the noise should make odometry drift";
  EXPECT_LT(error.rmse_m, 0.07);
  EXPECT_LT(error.max_m, 0.2);
  const auto relations = evaluation::EvaluateRelations(estimate, evaluation::MakeRelations(reference));
  EXPECT_LT(relations.translation_m.mean, 0.03);
  EXPECT_LT(relations.rotation_deg.mean, 0.5);
}

// A ring road 100 x 50 m between walls 8 m apart, with pillars at irregular spacing along
// both walls (seeded), so matches pin the motion down along the road too.
std::vector<Segment> RingRoad() {
  std::vector<Segment> world;
  AddBox(world, 0, 0, 100, 50);
  AddBox(world, 8, 8, 92, 42);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> gap(4.0, 9.0);
  for (double s = 2.0; s < 98.0; s += gap(random)) {
    AddBox(world, s, 0.0, s + 0.8, 0.6);
    AddBox(world, s + 1.5, 49.4, s + 2.3, 50.0);
    AddBox(world, s + 3.0, 7.4, s + 3.6, 8.0);
  }
  for (double s = 2.0; s < 48.0; s += gap(random)) {
    AddBox(world, 0.0, s, 0.6, s + 0.8);
    AddBox(world, 99.4, s + 1.0, 100.0, s + 1.8);
  }
  return world;
}

// One lap of the ring's centre line and 20 m more, a pose every metre, turning on the spot.
std::vector<Se2> LapAndOverlap() {
  const Eigen::Vector2d corners[4] = {{4, 4}, {96, 4}, {96, 46}, {4, 46}};
  std::vector<Se2> path;
  for (int side = 0; side < 5; ++side) {
    const Eigen::Vector2d from = corners[side % 4], to = corners[(side + 1) % 4];
    const double heading = std::atan2(to.y() - from.y(), to.x() - from.x());
    const int steps = side < 4 ? static_cast<int>((to - from).norm()) : 20;
    for (int i = 0; i < steps; ++i) path.emplace_back(from + (to - from).normalized() * i, heading);
    if (side == 4) break;
    for (int k = 1; k < 4; ++k) path.emplace_back(to, heading + k * std::numbers::pi / 8);
  }
  return path;
}

// Wheel and gyro odometry: exact steps, but the heading drifts by `bias` rad per metre
// driven, the way a gyro bias turns the whole trajectory.
std::vector<Se2> BiasedOdometry(const std::vector<Se2>& truth, double bias) {
  std::vector<Se2> odometry{truth.front()};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Se2 step = truth[i - 1].Inverse() * truth[i];
    odometry.push_back(odometry.back() * Se2(step.translation(), step.theta() + bias * step.translation().norm()));
  }
  return odometry;
}

TEST(MapBuilder, ClosesALapWhoseDriftIsBeyondTheLoopRadius) {
  const auto world = RingRoad();
  const auto truth = LapAndOverlap();
  const auto odometry = BiasedOdometry(truth, 6e-4);  // 0.16 rad over the lap
  MapBuilderOptions options;
  options.odometry = {0.01, 0.01, 0.01, 0.005, 0.0, 1};
  options.refine_sweeps = 1;
  options.keyframe_distance_m = 1.0;
  MapBuilder builder(options);
  builder.SetAnchor(truth.front());
  const auto [reference, drifted, estimate] = DriveThrough(builder, world, truth, odometry, 13);

  // Back at the start the odometry is metres from it: farther than loop_radius_m, so a
  // fixed search radius would not even try the lap's closure.
  const std::size_t lap_end = truth.size() - 21;
  const double lap_drift = (odometry[lap_end].translation() - truth[lap_end].translation()).norm();
  const MapBuilderStats& stats = builder.stats();
  const auto odometry_error = evaluation::EvaluateTrajectory(drifted, reference, /*align=*/false);
  const auto error = evaluation::EvaluateTrajectory(estimate, reference, /*align=*/false);
  std::printf("drift at the lap's end %.2f m; odometry ATE rmse %.3f m; builder ATE rmse %.3f m, max %.3f m; "
              "loops %llu (%llu closing a drift, %llu gated, %llu off)\n",
              lap_drift, odometry_error.rmse_m, error.rmse_m, error.max_m,
              static_cast<unsigned long long>(stats.loop_accepted), static_cast<unsigned long long>(stats.loop_drift_closed),
              static_cast<unsigned long long>(stats.loop_gated), static_cast<unsigned long long>(stats.loop_switched_off));
  EXPECT_GT(lap_drift, options.loop_radius_m + 1.0);
  EXPECT_GE(stats.loop_drift_closed, 1u);
  EXPECT_GE(stats.loop_accepted, 5u);
  EXPECT_EQ(stats.loop_switched_off, 0u);
  EXPECT_LT(error.rmse_m, 0.25);
  EXPECT_LT(error.max_m, 0.6);
}

// Wheel odometry whose distances are `scale` times the truth's (a wheel-radius error).
std::vector<Se2> ScaledOdometry(const std::vector<Se2>& truth, double scale) {
  std::vector<Se2> odometry{truth.front()};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Se2 step = truth[i - 1].Inverse() * truth[i];
    odometry.push_back(odometry.back() * Se2(scale * step.translation(), step.theta()));
  }
  return odometry;
}

// Odometry 0.6 % long (a wheel-radius error) and the scale estimate off: the map is as long
// as the odometry says unless the builder is given the calibrated scale.
TEST(MapBuilder, TakesACalibratedOdometryScale) {
  const auto world = RingRoad();
  const auto truth = LapAndOverlap();
  const double wheel_scale = 1.006;
  const auto odometry = ScaledOdometry(truth, wheel_scale);
  const auto build = [&](double scale) {
    MapBuilderOptions options;
    options.odometry = {0.01, 0.01, 0.01, 0.005, 0.0, 1};
    options.refine_sweeps = 0;
    options.keyframe_distance_m = 1.0;
    options.estimate_odometry_scale = false;
    options.odometry_scale = scale;
    MapBuilder builder(options);
    builder.SetAnchor(truth.front());
    const auto [reference, drifted, estimate] = DriveThrough(builder, world, truth, odometry, 17);
    EXPECT_EQ(builder.stats().odometry_scale, scale);
    return evaluation::EvaluateTrajectory(estimate, reference, /*align=*/false);
  };
  const auto nominal = build(1.0);
  const auto calibrated = build(1.0 / wheel_scale);
  std::printf("ATE rmse with the nominal scale %.3f m, with the calibrated scale %.3f m\n", nominal.rmse_m,
              calibrated.rmse_m);
  EXPECT_LT(calibrated.rmse_m, 0.1);
  EXPECT_GT(nominal.rmse_m, 2.0 * calibrated.rmse_m);
}

TEST(MapBuilder, KeepsKeyframesByDistanceAndTurn) {
  MapBuilderOptions options;
  options.keyframe_distance_m = 1.0;
  options.keyframe_angle_rad = 0.5;
  MapBuilder builder(options);
  const std::vector<Eigen::Vector2d> none;
  EXPECT_TRUE(builder.AddScan(0.0, Se2(0, 0, 0), none));
  EXPECT_FALSE(builder.AddScan(0.1, Se2(0.5, 0, 0), none));
  EXPECT_TRUE(builder.AddScan(0.2, Se2(1.0, 0, 0), none));
  EXPECT_TRUE(builder.AddScan(0.3, Se2(1.0, 0, 0.6), none));  // a turn on the spot
  EXPECT_EQ(builder.keyframes().size(), 3u);
  EXPECT_EQ(builder.stats().tracking_rejected, 2u);  // no points: odometry only
  builder.Finish();
  // Without matches the estimate is the odometry, anchored at the first keyframe.
  const Se2 corrected = builder.CorrectedPose(0.25, Se2(1.0, 0.0, 0.3));
  EXPECT_NEAR(corrected.x(), 1.0, 1e-9);
  EXPECT_NEAR(corrected.theta(), 0.3, 1e-9);
}

}  // namespace
}  // namespace flat2d::localization::mapping
