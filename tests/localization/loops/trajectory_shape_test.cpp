#include "localization/loops/trajectory_shape.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "localization/loops/local_map_trajectory.hpp"
#include "tests/testing/sanitizer.hpp"

namespace flat2d::localization::loops {
namespace {

// A planar path from curvatures: `steps` poses `step_m` apart, the heading turning by
// curvature(s) per metre; z rises slowly so the fit is 3D.
std::vector<Eigen::Isometry3d> PathOf(double length_m, double step_m, double (*curvature)(double)) {
  std::vector<Eigen::Isometry3d> path;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double heading = 0.0;
  for (double s = 0.0; s <= length_m + 1e-9; s += step_m) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = position + Eigen::Vector3d(0, 0, 0.02 * s);
    path.push_back(pose);
    heading += curvature(s) * step_m;
    position += step_m * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
  }
  return path;
}

double SCurve(double s) { return s < 20.0 ? 0.0 : s < 35.0 ? 0.1 : s < 45.0 ? -0.15 : 0.0; }
double Straight(double) { return 0.0; }
double QuarterCircle(double) { return M_PI / 2.0 / 5.0; }

Eigen::Isometry3d RandomTransform(std::mt19937& random, double max_offset_m) {
  std::uniform_real_distribution<double> offset(-max_offset_m, max_offset_m), angle(-M_PI, M_PI), tilt(-0.05, 0.05);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt(random), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(tilt(random), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  // Braces: the draws are made in order (a call's arguments have none).
  t.translation() = Eigen::Vector3d{offset(random), offset(random), 0.1 * offset(random)};
  return t;
}

TEST(TrajectoryShape, TheJacobianMatchesNumericDifferences) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d t = RandomTransform(random, 5.0), a = RandomTransform(random, 5.0), b = RandomTransform(random, 5.0);
    const ShapeLinearization analytic = LinearizeShapeError(t, a, b);
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
      delta(k) = 1e-6;
      Eigen::Isometry3d plus = t, minus = t;
      plus.translation() += delta.head<3>();
      minus.translation() -= delta.head<3>();
      plus.linear() = t.linear() * Eigen::AngleAxisd(1e-6, Eigen::Vector3d::Unit(k % 3)).toRotationMatrix();
      minus.linear() = t.linear() * Eigen::AngleAxisd(-1e-6, Eigen::Vector3d::Unit(k % 3)).toRotationMatrix();
      if (k < 3) plus.linear() = minus.linear() = t.linear();
      const Eigen::Matrix<double, 6, 1> error_plus = LinearizeShapeError(plus, a, b).error;
      const Eigen::Matrix<double, 6, 1> error_minus = LinearizeShapeError(minus, a, b).error;
      const Eigen::Matrix<double, 6, 1> numeric = (error_plus - error_minus) / 2e-6;
      EXPECT_LT((numeric - analytic.jacobian.col(k)).norm(), 1e-6) << "trial " << trial << " column " << k;
    }
  }
}

// Thesis Eq. 6.13 on a drive passed twice: the second pass sampled at another speed and
// phase, in a frame moved by a random transform, with centimetre noise. Seed 42, 50 cases.
TEST(TrajectoryShape, RecoversTheTransformBetweenTwoPassesOfOnePath) {
  const std::vector<Eigen::Isometry3d> reference = PathOf(60.0, 0.8, SCurve);
  std::mt19937 random(42);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::uniform_real_distribution<double> phase(0.0, 0.5);
  // Under the sanitizers 10 cases, half of them far.
  const int trials = testing::kSanitized ? 10 : 50;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Isometry3d reference_T_current = RandomTransform(random, trial < trials / 2 ? 3.0 : 200.0);
    // The second pass: poses every 0.5 m from a phase offset, in the current map's frame.
    const double start = phase(random);
    std::vector<Eigen::Isometry3d> current;
    const std::vector<double> arcs = ArcLengths(reference);
    for (double s = start; s < 58.0; s += 0.5) {
      Eigen::Isometry3d pose = reference_T_current.inverse() * PoseAlongPath(reference, arcs, s);
      pose.translation() += Eigen::Vector3d{noise(random), noise(random), noise(random)};
      current.push_back(pose);
    }
    // The association: the current pose about 30 m along with the reference pose at 30.4 m,
    // up to a pose spacing off along the path, as a random association would be.
    const int current_seed = static_cast<int>((30.0 - start) / 0.5);
    const ShapeAlignment fit = AlignTrajectories(reference, current, 38, current_seed);
    // The error where the paths are (the seed pose), not at the frame's origin 200 m away.
    const Eigen::Isometry3d& seed_pose = current[static_cast<std::size_t>(current_seed)];
    const Eigen::Isometry3d error = (reference_T_current * seed_pose).inverse() * (fit.reference_T_current * seed_pose);
    std::printf("trial %d: %.3f m %.3f deg, rms %.3f m, matched %.1f m\n", trial, error.translation().norm(),
                Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, fit.rms_translation_m, fit.matched_length_m);
    EXPECT_LT(error.translation().norm(), 0.10) << "trial " << trial;
    EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle(), 0.5 * M_PI / 180.0) << "trial " << trial;
    EXPECT_LT(fit.rms_translation_m, 0.08);  // 2 cm per axis on every current position
    EXPECT_GT(fit.matched_length_m, 50.0);
  }
}

TEST(TrajectoryShape, TheCorrespondencesStopWhereThePassesPart) {
  // The same 40 m, then the reference goes straight on and the current pass turns off.
  const std::vector<Eigen::Isometry3d> reference = PathOf(60.0, 0.5, [](double s) { return s < 20.0 ? 0.0 : s < 30.0 ? 0.12 : 0.0; });
  const std::vector<Eigen::Isometry3d> current =
      PathOf(60.0, 0.5, [](double s) { return s < 20.0 ? 0.0 : s < 30.0 ? 0.12 : s < 40.0 ? 0.0 : 0.2; });
  const ShapeAlignment fit = AlignTrajectories(reference, current, 50, 50);
  EXPECT_LT(fit.reference_T_current.translation().norm(), 0.05);
  EXPECT_LT(Eigen::AngleAxisd(fit.reference_T_current.linear()).angle(), 0.2 * M_PI / 180.0);
  EXPECT_LT(fit.rms_translation_m, 0.15);  // the parting pairs, up to the 1 m gate, are in it
  // The turn-off leaves the 1 m gate about 3 m after it starts: 40 to 43 m matched.
  EXPECT_GT(fit.matched_length_m, 40.0);
  EXPECT_LT(fit.matched_length_m, 45.0);
}

TEST(TrajectoryShape, ABadSeedGivesNoPairs) {
  const std::vector<Eigen::Isometry3d> path = PathOf(10.0, 1.0, Straight);
  EXPECT_EQ(AlignTrajectories(path, path, -1, 0).pairs, 0);
  EXPECT_EQ(AlignTrajectories(path, path, 0, 100).pairs, 0);
  EXPECT_EQ(AlignTrajectories({}, path, 0, 0).pairs, 0);
}

TEST(LocalMapTrajectory, AStraightPathIsNotInformativeATurnIs) {
  const std::vector<Eigen::Isometry3d> straight = PathOf(5.0, 0.5, Straight);
  const Eigen::Vector3d spread = TrajectorySpread(straight);
  // n evenly spaced points h apart: standard deviation h sqrt((n^2 - 1) / 12); 11 points 0.5 m apart.
  EXPECT_NEAR(spread(0), 0.5 * std::sqrt(120.0 / 12.0), 0.005);
  EXPECT_LT(spread(1), 1e-9);
  EXPECT_FALSE(IsInformative(straight, 0.05));
  const std::vector<Eigen::Isometry3d> turn = PathOf(5.0, 0.5, QuarterCircle);
  EXPECT_GT(TrajectorySpread(turn)(1), 0.3);
  EXPECT_TRUE(IsInformative(turn, 0.05));
}

TEST(LocalMapTrajectory, PathAroundAMapReassemblesTheDrive) {
  const std::vector<Eigen::Isometry3d> drive = PathOf(60.0, 0.5, SCurve);
  std::vector<LocalMapTrajectory> maps;
  for (std::size_t first = 0; first + 1 < drive.size(); first += 10) {
    LocalMapTrajectory map;
    map.world_T_map = drive[first];
    map.path_start_m = 0.5 * static_cast<double>(first);
    for (std::size_t k = first; k <= std::min(first + 10, drive.size() - 1); ++k) map.map_T_pose.push_back(drive[first].inverse() * drive[k]);
    maps.push_back(map);
  }
  const PathAround path = PathAroundMap(maps, 5, 9.0, 9.0);
  // Map 5 starts at pose 50; 9 m either side reaches into two maps of 5 m: poses 30 to 80.
  ASSERT_EQ(path.map_T_pose.size(), 51u);
  EXPECT_EQ(path.first_own, 20);
  EXPECT_EQ(path.own_count, 11);
  EXPECT_NEAR(path.length_m, 25.0, 0.01);  // the path climbs 2 %
  for (std::size_t k = 0; k < path.map_T_pose.size(); ++k) {
    const Eigen::Isometry3d expected = drive[50].inverse() * drive[30 + k];
    EXPECT_LT((path.map_T_pose[k].matrix() - expected.matrix()).norm(), 1e-9) << k;
  }
}

}  // namespace
}  // namespace flat2d::localization::loops
