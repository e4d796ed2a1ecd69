#include "localization/evaluation/relations.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"

namespace flat2d::localization::evaluation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 10 x 10 m square driven once, a pose every 0.25 m, heading along the path.
std::vector<TimedPose> Square() {
  std::vector<TimedPose> poses;
  double t = 0.0;
  for (int side = 0; side < 4; ++side) {
    const Se2 corner = side == 0 ? Se2() : poses.back().pose * Se2(0.25, 0.0, 0.0);
    for (int i = 0; i < 40; ++i) {
      poses.push_back({t, Se2(corner.translation(), side * std::numbers::pi / 2) * Se2(0.25 * i, 0.0, 0.0)});
      t += 0.5;
    }
  }
  return poses;
}

TEST(Relations, ParsesTheFreiburgFormatAndNamesBadLines) {
  auto relations = ParseRelations("# comment\n976052857.3 976052858.2 1.5 -0.25 0 0 0 0.1\n\n1 2 3 4 0 0 0 -3\n", "r");
  ASSERT_TRUE(relations.ok()) << relations.error().message;
  ASSERT_EQ(relations->size(), 2u);
  EXPECT_DOUBLE_EQ((*relations)[0].t1, 976052857.3);
  EXPECT_DOUBLE_EQ((*relations)[0].delta.x(), 1.5);
  EXPECT_DOUBLE_EQ((*relations)[0].delta.y(), -0.25);
  EXPECT_DOUBLE_EQ((*relations)[0].delta.theta(), 0.1);

  auto bad = ParseRelations("1 2 3 4 0 0 0 0.1\n1 2 three 4 0 0 0 0\n", "intel.relations");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("intel.relations:2"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(ParseRelations("1 2 3 4 0 0 0 0.1 9\n", "r").ok());  // a ninth field
  EXPECT_FALSE(ParseRelations("", "r").ok());
  EXPECT_FALSE(ParseRelations("1 2 nan 4 0 0 0 0\n", "r").ok());
}

TEST(Relations, ExactEstimateHasNoError) {
  const auto reference = Square();
  const auto relations = MakeRelations(reference);
  ASSERT_GT(relations.size(), 100u);
  const RelationsError e = EvaluateRelations(reference, relations);
  EXPECT_EQ(e.relations, relations.size());
  EXPECT_EQ(e.unmatched, 0u);
  EXPECT_NEAR(e.translation_m.mean, 0.0, 1e-12);
  EXPECT_NEAR(e.rotation_deg.mean, 0.0, 1e-9);
}

TEST(Relations, MeasuresKnownTranslationAndRotationErrors) {
  // The estimate at t = 1 is 0.1 m further on and turned 2 degrees: the relation (0, 1) is
  // off by 0.1 m and 2 deg, the relation (1, 2) by 2 deg and 0.1 m back, rotated.
  const std::vector<TimedPose> reference = {{0.0, Se2(0, 0, 0)}, {1.0, Se2(1, 0, 0)}, {2.0, Se2(2, 0, 0)}};
  std::vector<TimedPose> estimate = reference;
  estimate[1].pose = Se2(1.1, 0.0, 2.0 * kDeg);
  std::vector<Relation> relations = {{0.0, 1.0, Se2(1, 0, 0)}};
  RelationsError e = EvaluateRelations(estimate, relations);
  ASSERT_EQ(e.relations, 1u);
  EXPECT_NEAR(e.translation_m.mean, 0.1, 1e-12);
  EXPECT_NEAR(e.rotation_deg.mean, 2.0, 1e-9);
  EXPECT_NEAR(e.translation_sq_m2.mean, 0.01, 1e-12);
  EXPECT_NEAR(e.rotation_sq_deg2.mean, 4.0, 1e-9);
  EXPECT_NEAR(e.translation_m.std, 0.0, 1e-12);

  relations.push_back({0.0, 2.0, Se2(2, 0, 0)});  // unaffected by pose 1
  e = EvaluateRelations(estimate, relations);
  EXPECT_NEAR(e.translation_m.mean, 0.05, 1e-12);
  EXPECT_NEAR(e.translation_m.std, 0.05, 1e-12);
  EXPECT_NEAR(e.rotation_deg.mean, 1.0, 1e-9);
}

TEST(Relations, InterpolatesAndCountsTimesOutsideTheEstimate) {
  const std::vector<TimedPose> estimate = {{0.0, Se2(0, 0, 0)}, {1.0, Se2(1, 0, 0)}, {5.0, Se2(5, 0, 0)}};
  Se2 pose;
  ASSERT_TRUE(PoseAt(estimate, 0.25, 1.0, pose));
  EXPECT_NEAR(pose.x(), 0.25, 1e-12);
  EXPECT_FALSE(PoseAt(estimate, 3.0, 1.0, pose));  // inside a 4 s gap
  EXPECT_TRUE(PoseAt(estimate, 3.0, 5.0, pose));
  EXPECT_FALSE(PoseAt(estimate, -0.1, 1.0, pose));
  EXPECT_TRUE(PoseAt(estimate, 5.0, 1.0, pose));  // an exact hit on the last pose
  const RelationsError e = EvaluateRelations(estimate, {{0.0, 0.5, Se2(0.5, 0, 0)}, {0.0, 7.0, Se2()}});
  EXPECT_EQ(e.relations, 1u);
  EXPECT_EQ(e.unmatched, 1u);
}

TEST(Relations, DrawsLocalAndRevisitRelationsFromAReference) {
  auto reference = Square();
  // Drive the first side again: the revisits of the start.
  const double t0 = reference.back().time_s;
  for (int i = 0; i < 20; ++i) reference.push_back({t0 + 0.5 * (i + 1), Se2(0.25 * i, 0.05, 0.0)});
  RelationSampling sampling;
  sampling.min_step_m = 1.0;
  const auto relations = MakeRelations(reference, sampling);
  int local = 0, revisit = 0;
  for (const Relation& r : relations) {
    if (r.t2 - r.t1 < 10.0) {
      ++local;
      EXPECT_NEAR(r.delta.translation().norm(), 1.0, 0.3);
    } else {
      ++revisit;
      EXPECT_LT(r.delta.translation().norm(), sampling.loop_radius_m);
    }
  }
  EXPECT_GT(local, 150);
  EXPECT_GE(revisit, 18);  // the second pass along the first side
}

TEST(TrajectoryError, AlignmentRemovesARigidMotion) {
  const auto reference = Square();
  const Se2 offset(3.0, -2.0, 30.0 * kDeg);
  std::vector<TimedPose> estimate;
  for (const auto& p : reference) estimate.push_back({p.time_s, offset * p.pose});
  const TrajectoryError aligned = EvaluateTrajectory(estimate, reference);
  EXPECT_EQ(aligned.poses, reference.size());
  EXPECT_NEAR(aligned.rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(aligned.rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_NEAR(aligned.reference_T_estimate.theta(), -30.0 * kDeg, 1e-9);
  const TrajectoryError raw = EvaluateTrajectory(estimate, reference, /*align=*/false);
  EXPECT_GT(raw.rmse_m, 2.0);
}

TEST(TrajectoryError, MeasuresAKnownOffset) {
  const auto reference = Square();
  std::vector<TimedPose> estimate = reference;
  estimate[10].pose = estimate[10].pose * Se2(0.0, 0.5, 0.0);  // one pose 0.5 m off
  const TrajectoryError e = EvaluateTrajectory(estimate, reference, /*align=*/false);
  EXPECT_NEAR(e.max_m, 0.5, 1e-12);
  EXPECT_NEAR(e.rmse_m, 0.5 / std::sqrt(static_cast<double>(reference.size())), 1e-12);
  EXPECT_NEAR(e.median_m, 0.0, 1e-12);
}

// Around the square, the estimate 0.1 m to the left of the truth and 0.02 m ahead, its
// heading off by 0.0005 rad and 0.001 rad more per pose (0.0005 .. 0.1595 rad, clear of
// the bins' edges).
TEST(TrajectoryError, SplitsPositionAlongAndAcrossTheHeadingAndBinsTheHeadingError) {
  const auto reference = Square();
  std::vector<TimedPose> estimate;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    estimate.push_back({reference[i].time_s, reference[i].pose * Se2(0.02, 0.1, 0.0005 + 0.001 * static_cast<double>(i))});
  }
  const TrajectoryError e = EvaluateTrajectory(estimate, reference, /*align=*/false);
  ASSERT_EQ(e.poses, 160u);
  EXPECT_NEAR(e.longitudinal_m.p99, 0.02, 1e-9);
  EXPECT_NEAR(e.lateral_m.p50, 0.1, 1e-9);
  EXPECT_NEAR(e.position_m.p95, std::hypot(0.02, 0.1), 1e-9);
  EXPECT_NEAR(e.heading_within_0_02, 20.0 / 160.0, 1e-12);
  EXPECT_NEAR(e.heading_within_0_025, 25.0 / 160.0, 1e-12);
  EXPECT_NEAR(e.heading_worst_rad, 0.1595, 1e-9);
  ASSERT_EQ(e.heading_histogram.size(), kHeadingBins);
  std::size_t total = 0;
  for (const std::size_t count : e.heading_histogram) total += count;
  EXPECT_EQ(total, 160u);
  EXPECT_EQ(e.heading_histogram[1], 5u);       // 0.0055 .. 0.0095 rad
  EXPECT_EQ(e.heading_histogram.back(), 60u);  // 0.1005 .. 0.1595 rad
}

TEST(TrajectoryError, PercentilesAreNearestRank) {
  const auto reference = Square();
  std::vector<TimedPose> estimate = reference;
  // Two poses of 160 off sideways: 1.25 % of them, inside the top 5 % but not the top 1 %.
  estimate[3].pose = estimate[3].pose * Se2(0.0, 1.0, 0.0);
  estimate[7].pose = estimate[7].pose * Se2(0.0, 2.0, 0.0);
  const TrajectoryError e = EvaluateTrajectory(estimate, reference, /*align=*/false);
  EXPECT_EQ(e.position_m.p50, 0.0);
  EXPECT_EQ(e.position_m.p95, 0.0);
  EXPECT_NEAR(e.position_m.p99, 1.0, 1e-9);  // the 159th of 160 sorted
  EXPECT_NEAR(e.lateral_m.p99, 1.0, 1e-9);
  EXPECT_EQ(e.longitudinal_m.p99, 0.0);
  EXPECT_NEAR(e.max_m, 2.0, 1e-9);
}

TEST(TrajectoryFile, RoundTripsThroughTum) {
  const auto reference = Square();
  const auto path = std::filesystem::temp_directory_path() / ("flat2d_traj_" + std::to_string(::getpid()) + ".tum");
  ASSERT_TRUE(WriteTrajectory(reference, path).ok());
  auto read = ReadTrajectory(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_EQ(read->size(), reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    EXPECT_NEAR((*read)[i].time_s, reference[i].time_s, 1e-9);
    EXPECT_NEAR((*read)[i].pose.x(), reference[i].pose.x(), 1e-6);
    EXPECT_NEAR(NormalizeAngle((*read)[i].pose.theta() - reference[i].pose.theta()), 0.0, 1e-8);
  }
}

}  // namespace
}  // namespace flat2d::localization::evaluation
