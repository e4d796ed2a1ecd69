// Landmark SLAM (thesis 8.2) on a synthetic loop: walls and poles, a drifting dead
// reckoning, noisy features with clutter (synthetic_landmark_drive.hpp). The first pose is
// the truth's, so errors are compared without alignment. Bounds are about 2-3x what the
// seeds give, so that a real regression fails and a change of noise draw does not.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "localization/landmarks/landmark_slam.hpp"
#include "tests/localization/landmarks/synthetic_landmark_drive.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::Drive;
using testing::DriveSettings;
using testing::MakeDrive;
using testing::MakeLoopWorld;

constexpr double kDegree = std::numbers::pi / 180.0;

struct SlamRun {
  double slam_rmse_m = 0.0;
  double odometry_rmse_m = 0.0;
  std::vector<hal::trajectory::StampedPose> trajectory;
  std::vector<LandmarkSlam::PlaneLandmark> planes;
  std::vector<LandmarkSlam::LineLandmark> lines;
  LandmarkSlamStats stats;
};

double PositionRmse(const Drive& drive, const std::vector<Eigen::Isometry3d>& estimate) {
  double sum = 0.0;
  for (std::size_t k = 0; k < estimate.size(); ++k) {
    sum += (estimate[k].translation() - drive.revolutions[k].truth_world_T_vehicle.translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(estimate.size()));
}

SlamRun RunSlam(const Drive& drive, const LandmarkSlamOptions& options) {
  LandmarkSlam slam(options, drive.vehicle_T_sensor);
  for (std::size_t k = 0; k < drive.revolutions.size(); ++k) {
    const testing::Revolution& r = drive.revolutions[k];
    slam.Add(static_cast<TimeNs>(k) * 100 * kNsPerMs, r.odometry_world_T_vehicle, r.features);
  }
  slam.Finish();
  SlamRun run;
  run.trajectory = slam.Trajectory();
  std::vector<Eigen::Isometry3d> estimate, odometry;
  for (std::size_t k = 0; k < run.trajectory.size(); ++k) {
    estimate.push_back(run.trajectory[k].world_T_body);
    odometry.push_back(drive.revolutions[k].odometry_world_T_vehicle);
  }
  run.slam_rmse_m = PositionRmse(drive, estimate);
  run.odometry_rmse_m = PositionRmse(drive, odometry);
  run.planes = slam.Planes();
  run.lines = slam.Lines();
  run.stats = slam.stats();
  const LandmarkSlamStats& s = run.stats;
  std::printf("rmse slam %.3f m, odometry %.3f m; nodes %d, planes %d, lines %d, factors %d + %d, new %d, "
              "associated %d, downweighted %d; %d optimizations, %d iterations, solve %.1f ms (last %.1f ms), back end %.2f ms/revolution\n",
              run.slam_rmse_m, run.odometry_rmse_m, s.pose_nodes, s.plane_landmarks, s.line_landmarks, s.plane_factors,
              s.line_factors, s.new_landmarks, s.associations, s.downweighted_factors, s.optimizations, s.iterations,
              s.solve_ms_total, s.last_solve_ms, s.backend_ms_total / s.revolutions);
  return run;
}

Drive SeededDrive(unsigned seed, const DriveSettings& settings) {
  std::printf("seed %u\n", seed);
  std::mt19937 world_rng(seed), noise_rng(seed + 1), corruption_rng(seed + 2);
  return MakeDrive(MakeLoopWorld(world_rng), settings, noise_rng, corruption_rng);
}

// SLAM landmarks (seen at least twice) that represent truth wall w: same orientation within
// 5 deg, centroid within 0.3 m of the wall's plane and over the wall (1 m margin).
int PlaneMatches(const SlamRun& run, const testing::Wall& wall) {
  const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ().cross(wall.Along());
  int matches = 0;
  for (const LandmarkSlam::PlaneLandmark& p : run.planes) {
    if (p.observations < 2) continue;
    const Eigen::Vector3d offset = p.centroid - wall.Center();
    if (std::abs(p.plane.normal.dot(normal)) < std::cos(5.0 * kDegree)) continue;
    if (std::abs(offset.dot(normal)) > 0.3 || std::abs(offset.dot(wall.Along())) > wall.HalfLength() + 1.0) continue;
    ++matches;
  }
  return matches;
}

// Line landmarks (seen at least twice) within 5 deg of vertical and 0.3 m of the pole.
int LineMatches(const SlamRun& run, const testing::Pole& pole) {
  int matches = 0;
  for (const LandmarkSlam::LineLandmark& l : run.lines) {
    if (l.observations < 2 || std::abs(l.direction.z()) < std::cos(5.0 * kDegree)) continue;
    // Where the landmark line crosses the pole's mid height.
    const Eigen::Vector3d mid = pole.base + 0.5 * pole.length * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d at = l.point + (mid.z() - l.point.z()) / l.direction.z() * l.direction;
    if ((at - mid).head<2>().norm() <= 0.3) ++matches;
  }
  return matches;
}

TEST(LandmarkSlam, LoopWithDriftingOdometryIsCorrectedByLandmarks) {
  const Drive drive = SeededDrive(8201, DriveSettings{});
  const SlamRun run = RunSlam(drive, LandmarkSlamOptions{});
  ASSERT_EQ(run.trajectory.size(), drive.revolutions.size());
  EXPECT_LE(run.slam_rmse_m * 3.0, run.odometry_rmse_m);
  EXPECT_LE(run.slam_rmse_m, 0.05);
  EXPECT_GE(run.odometry_rmse_m, 0.5) << "the drive must drift for the test to mean anything";
}

TEST(LandmarkSlam, EveryLandmarkInViewIsOneLandmark) {
  const Drive drive = SeededDrive(8202, DriveSettings{});
  const SlamRun run = RunSlam(drive, LandmarkSlamOptions{});
  int missing = 0, duplicates = 0, in_view = 0;
  for (std::size_t w = 0; w < drive.world.walls.size(); ++w) {
    if (drive.wall_sightings[w] < 3) continue;
    ++in_view;
    const int matches = PlaneMatches(run, drive.world.walls[w]);
    missing += matches == 0 ? 1 : 0;
    duplicates += std::max(matches - 1, 0);
    if (matches != 1) std::printf("wall %zu: %d landmarks (%d sightings)\n", w, matches, drive.wall_sightings[w]);
  }
  for (std::size_t p = 0; p < drive.world.poles.size(); ++p) {
    if (drive.pole_sightings[p] < 3) continue;
    ++in_view;
    const int matches = LineMatches(run, drive.world.poles[p]);
    missing += matches == 0 ? 1 : 0;
    duplicates += std::max(matches - 1, 0);
    if (matches != 1) std::printf("pole %zu: %d landmarks (%d sightings)\n", p, matches, drive.pole_sightings[p]);
  }
  std::printf("%d landmarks in view, %d missing, %d duplicates\n", in_view, missing, duplicates);
  EXPECT_GE(in_view, 50);
  EXPECT_EQ(missing, 0);
  EXPECT_LE(duplicates, 2);
}

TEST(LandmarkSlam, WrongAssociationsBarelyMoveTheTrajectory) {
  DriveSettings corrupted;
  corrupted.corrupted_fraction = 0.1;
  const Drive clean_drive = SeededDrive(8203, DriveSettings{});
  const Drive bad_drive = SeededDrive(8203, corrupted);
  const SlamRun clean = RunSlam(clean_drive, LandmarkSlamOptions{});
  const SlamRun robust = RunSlam(bad_drive, LandmarkSlamOptions{});
  LandmarkSlamOptions plain;
  plain.optimizer.kernel.kernel = RobustKernel::kNone;
  const SlamRun least_squares = RunSlam(bad_drive, plain);
  std::printf("rmse clean %.3f m, 10%% wrong with Cauchy %.3f m, without kernel %.3f m\n", clean.slam_rmse_m,
              robust.slam_rmse_m, least_squares.slam_rmse_m);
  EXPECT_GT(robust.stats.downweighted_factors, 0);
  EXPECT_LE(robust.slam_rmse_m - clean.slam_rmse_m, 0.03);
  EXPECT_LT(robust.slam_rmse_m, least_squares.slam_rmse_m) << "the kernel must be what helps";
}

TEST(LandmarkSlam, WithoutFeaturesTheTrajectoryIsTheOdometry) {
  DriveSettings settings;
  settings.features = false;
  const Drive drive = SeededDrive(8204, settings);
  const SlamRun run = RunSlam(drive, LandmarkSlamOptions{});
  ASSERT_EQ(run.trajectory.size(), drive.revolutions.size());
  double worst_m = 0.0, worst_rad = 0.0;
  for (std::size_t k = 0; k < run.trajectory.size(); ++k) {
    const Eigen::Isometry3d odometry = drive.revolutions[k].odometry_world_T_vehicle;
    EXPECT_EQ(run.trajectory[k].time_ns, static_cast<TimeNs>(k) * 100 * kNsPerMs);
    worst_m = std::max(worst_m, (run.trajectory[k].world_T_body.translation() - odometry.translation()).norm());
    worst_rad = std::max(worst_rad, Eigen::AngleAxisd(odometry.linear().transpose() * run.trajectory[k].world_T_body.linear()).angle());
  }
  EXPECT_LE(worst_m, 1e-9);
  EXPECT_LE(worst_rad, 1e-9);
  EXPECT_TRUE(run.planes.empty());
  EXPECT_TRUE(run.lines.empty());
  EXPECT_GT(run.stats.pose_nodes, 50);
}

TEST(LandmarkSlam, PoleThroughTheWorldOriginIsEstimated) {
  const Drive drive = SeededDrive(8205, DriveSettings{});
  const SlamRun run = RunSlam(drive, LandmarkSlamOptions{});
  const testing::Pole& pole = drive.world.poles[static_cast<std::size_t>(drive.world.origin_pole)];
  ASSERT_EQ(pole.base.norm(), 0.0);
  int found = 0;
  for (const LandmarkSlam::LineLandmark& l : run.lines) {
    if (l.observations < 10) continue;
    const Eigen::Vector3d direction = l.direction.z() < 0.0 ? Eigen::Vector3d(-l.direction) : l.direction;
    // The landmark line's distance from the world's z axis and its tilt.
    const double distance = (l.point - l.point.dot(direction) * direction).norm();
    if (distance > 0.5) continue;
    ++found;
    std::printf("origin pole: %d observations, %.3f m from the axis, tilt %.2f deg\n", l.observations, distance,
                std::acos(direction.z()) / kDegree);
    EXPECT_LE(distance, 0.05);
    EXPECT_LE(std::acos(std::min(direction.z(), 1.0)), 1.0 * kDegree);
  }
  EXPECT_EQ(found, 1);
}

// The office drive's size: 3600 revolutions over 428 m, ~25 features each, 0.5 m keyframes.
// Its time per revolution is tests/bench/landmark_slam_bench's (target 20 ms).
TEST(LandmarkSlam, OfficeSizedDriveStaysAccurate) {
  const unsigned seed = 8206;
  std::printf("seed %u\n", seed);
  const Drive drive = testing::OfficeSizedDrive(seed);
  const SlamRun run = RunSlam(drive, LandmarkSlamOptions{});
  EXPECT_LE(run.slam_rmse_m * 3.0, run.odometry_rmse_m);
  EXPECT_LE(run.slam_rmse_m, 0.5);
}

}  // namespace
}  // namespace flat2d::localization::landmarks
