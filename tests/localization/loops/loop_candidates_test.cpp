#include "localization/loops/loop_candidates.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "hal/trajectory/kitti_pose_file.hpp"
#include "localization/evaluation/loop_candidate_eval.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/sanitizer.hpp"

namespace flat2d::localization::loops {
namespace {

// A closed block with four 90-degree left corners of radii 8, 12, 6 and 15 m and the
// straights that close it (60, 40, 65 and 39 m), driven `laps` times with poses every
// 0.5 m, in closed form so that the laps lie exactly on one another.
std::vector<Eigen::Isometry3d> BlockDrive(double laps) {
  struct Stretch {
    double length_m;
    double radius_m;  // 0: straight
  };
  const std::vector<Stretch> lap{{60, 0}, {M_PI * 8 / 2, 8}, {40, 0}, {M_PI * 12 / 2, 12},
                                 {65, 0}, {M_PI * 6 / 2, 6},  {39, 0}, {M_PI * 15 / 2, 15}};
  double lap_length = 0.0;
  for (const auto& stretch : lap) lap_length += stretch.length_m;
  const auto pose_at = [&](double s) {
    s = std::fmod(s, lap_length);
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    double heading = 0.0;
    for (const auto& stretch : lap) {
      const double along = std::min(s, stretch.length_m);
      const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
      if (stretch.radius_m == 0.0) {
        position += along * direction;
      } else {
        const double turn = along / stretch.radius_m;
        position += stretch.radius_m * Eigen::Vector2d(std::sin(heading + turn) - std::sin(heading),
                                                       std::cos(heading) - std::cos(heading + turn));
        heading += turn;
      }
      s -= along;
      if (s <= 0.0) break;
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() << position, 0.0;
    return pose;
  };
  std::vector<Eigen::Isometry3d> drive;
  for (double s = 0.0; s < laps * lap_length; s += 0.5) drive.push_back(pose_at(s));
  return drive;
}

TEST(LoopCandidates, TheBlockCloses) {
  const std::vector<Eigen::Isometry3d> drive = BlockDrive(1.0);
  const Eigen::Isometry3d last = drive.back();
  // The lap is 343.2 m: the last pose is under 0.5 m before the start, in the last corner
  // (radius 15 m): under 0.5 / 15 rad short of heading east again.
  EXPECT_LT(last.translation().norm(), 0.5);
  EXPECT_LT(Eigen::AngleAxisd(last.linear()).angle(), 0.5 / 15.0);
}

// Under the sanitizers, where the search runs some forty times slower, 1.3 laps: the
// second lap's first 100 m revisit the first corner only.
const double kLaps = testing::kSanitized ? 1.3 : 2.2;

evaluation::LoopEvalOptions BlockOptions() {
  evaluation::LoopEvalOptions options;
  options.drift.yaw_bias_deg_per_m = 0.03;  // 10 deg over a lap: the distance search is blind by the second
  // The drift bound: the other corners lie 50 m and more away, 1 to 2 laps back.
  options.candidates.drift_fraction = 0.1;
  return options;
}

TEST(LoopCandidates, TrajectoryShapeFindsTheRevisitsThatDistanceMisses) {
  const std::vector<Eigen::Isometry3d> truth = BlockDrive(kLaps);
  const evaluation::LoopEvalReport report = evaluation::EvaluateLoopCandidates(truth, BlockOptions());
  std::printf("%d maps, %d informative; revisits %d (%d informative); final drift %.1f m\n", report.maps,
              report.informative_maps, report.revisits, report.informative_revisits, report.final_drift_m);
  std::printf("distance: %d candidates, %d correct, recall %.3f; shape: %d candidates, %d correct, recall %.3f\n",
              report.distance.candidates, report.distance.correct, report.recall(report.distance), report.shape.candidates,
              report.shape.correct, report.recall(report.shape));
  ASSERT_GT(report.informative_revisits, testing::kSanitized ? 2 : 10);
  EXPECT_GT(report.final_drift_m, testing::kSanitized ? 3.0 : 10.0);
  // Every corner revisited is found, its guess within 1 m and 5 deg, and nothing else is.
  EXPECT_GE(report.recall(report.shape), 0.9);
  EXPECT_GE(report.shape.precision(), 0.9);
  EXPECT_LT(report.recall(report.distance), 0.5);
}

TEST(LoopCandidates, WithoutDriftTheDistanceSearchFindsThemToo) {
  if (testing::kSanitized) GTEST_SKIP() << "the drifted case above runs the same code; the release build runs this";
  evaluation::LoopEvalOptions options = BlockOptions();
  options.drift = {0.0, 0.0, 0.0, 0.0, 0.0, 1};
  const evaluation::LoopEvalReport report = evaluation::EvaluateLoopCandidates(BlockDrive(kLaps), options);
  EXPECT_LT(report.final_drift_m, 1e-9);
  EXPECT_EQ(report.distance.all_revisits_found, report.revisits);
  EXPECT_GE(report.recall(report.shape), 0.9);
}

TEST(LoopCandidates, NoLoopNoCandidate) {
  const evaluation::LoopEvalReport report = evaluation::EvaluateLoopCandidates(BlockDrive(0.95), BlockOptions());
  EXPECT_EQ(report.revisits, 0);
  EXPECT_EQ(report.shape.candidates, 0);
  EXPECT_EQ(report.distance.candidates, 0);
}

// KITTI odometry 00's truth (4541 poses, 3.7 km) drifted by the default model (42 m off
// at the end), cut in 5 m maps. Figures in docs/benchmarks.md; the bounds sit below them.
TEST(LoopCandidates, Kitti00TruthTrajectory) {
  if (testing::kSanitized) GTEST_SKIP() << "3.7 km of loop search: the release build runs it";
  FLAT2D_REQUIRE_DATA(path, "lidar3d/kitti_odometry_00_frames_000000-000015/poses_00_full_4541.txt");
  const auto poses = hal::trajectory::ReadKittiPoses(path);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  std::vector<Eigen::Isometry3d> truth;
  for (const auto& pose : *poses) truth.push_back(hal::trajectory::VehicleFromKittiCamera(pose));
  evaluation::LoopEvalOptions options;
  options.candidates.drift_fraction = 0.05;
  const evaluation::LoopEvalReport report = evaluation::EvaluateLoopCandidates(truth, options);
  std::printf("maps %d (%d informative), revisits %d (%d informative), drift %.1f m; shape %d candidates, %d correct, "
              "recall %.3f; distance %d candidates, %d correct\n",
              report.maps, report.informative_maps, report.revisits, report.informative_revisits, report.final_drift_m,
              report.shape.candidates, report.shape.correct, report.recall(report.shape), report.distance.candidates,
              report.distance.correct);
  EXPECT_EQ(report.maps, 690);
  EXPECT_GE(report.recall(report.shape), 0.4);
  EXPECT_GE(report.shape.precision(), 0.3);
  EXPECT_EQ(report.distance.correct, 0);  // 42 m of drift: the distance search's guesses are all beyond 1 m
}

// Tie i joins maps i and i + 1: with tie 2 failed (maps 2 -> 3), only the chains that span
// it cross a failure, whichever way round they are asked.
TEST(ChainCrossesFailure, OnlyChainsSpanningAFailedTieCrossOne) {
  const std::vector<bool> tie_failed{false, false, true, false};  // maps 0..4
  EXPECT_FALSE(ChainCrossesFailure(tie_failed, 0, 2));
  EXPECT_TRUE(ChainCrossesFailure(tie_failed, 0, 3));
  EXPECT_TRUE(ChainCrossesFailure(tie_failed, 2, 3));
  EXPECT_TRUE(ChainCrossesFailure(tie_failed, 4, 1));
  EXPECT_FALSE(ChainCrossesFailure(tie_failed, 3, 4));
  EXPECT_FALSE(ChainCrossesFailure(tie_failed, 2, 2));
  EXPECT_FALSE(ChainCrossesFailure({}, 0, 5));  // a chain of one map
  EXPECT_TRUE(ChainCrossesFailure(tie_failed, -1, 9));  // map indices beyond the chain are clamped
}

}  // namespace
}  // namespace flat2d::localization::loops
