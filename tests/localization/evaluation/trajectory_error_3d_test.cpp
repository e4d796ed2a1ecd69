#include "localization/evaluation/trajectory_error_3d.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "tests/testing/data_path.hpp"

namespace flat2d::localization::evaluation {
namespace {

using hal::trajectory::StampedPose;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr TimeNs kStartNs = 1'305'031'225 * kNsPerSecond;  // fr1's epoch, to keep the times' magnitude
constexpr TimeNs kStepNs = 10 * kNsPerMs;                   // 100 Hz, as the benchmark's truth

Eigen::Isometry3d Pose(const Eigen::Vector3d& position, double yaw, double pitch, double roll) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = position;
  return pose;
}

// A hand-held camera's kind of motion: an ellipse with a bob, turning, nodding and rolling.
std::vector<StampedPose> Truth(int poses = 600) {
  std::vector<StampedPose> out;
  for (int i = 0; i < poses; ++i) {
    const double t = 0.01 * i;
    const Eigen::Vector3d p(2.0 * std::cos(0.5 * t), 1.5 * std::sin(0.5 * t), 0.3 * std::sin(t));
    out.push_back({kStartNs + i * kStepNs, Pose(p, 0.5 * t + std::numbers::pi / 2, 0.2 * std::sin(0.7 * t),
                                                0.1 * std::cos(1.3 * t))});
  }
  return out;
}

Eigen::Isometry3d RandomMotion(std::mt19937& rng, double max_offset_m) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d{unit(rng), unit(rng), unit(rng)}.normalized();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(std::numbers::pi * unit(rng), axis).toRotationMatrix();
  motion.translation() = max_offset_m * Eigen::Vector3d{unit(rng), unit(rng), unit(rng)};
  return motion;
}

double AngleDeg(const Eigen::Matrix3d& rotation) {
  // Not AngleAxis: the quaternion's half-angle form, written out.
  const Eigen::Quaterniond q(rotation);
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) / kDeg;
}

double Rms(const std::vector<double>& v) {
  double squares = 0.0;
  for (const double x : v) squares += x * x;
  return std::sqrt(squares / static_cast<double>(v.size()));
}

double NearestRankMedian(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[(v.size() + 1) / 2 - 1];
}

// ATE by Horn's quaternion method (Horn 1987): the rotation is the eigenvector of the largest
// eigenvalue of his 4 x 4 matrix N, independent of the library's SVD.
double HornAteRmse(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to) {
  Eigen::Vector3d mean_from = Eigen::Vector3d::Zero(), mean_to = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    mean_from += from[i];
    mean_to += to[i];
  }
  mean_from /= static_cast<double>(from.size());
  mean_to /= static_cast<double>(from.size());
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) s += (from[i] - mean_from) * (to[i] - mean_to).transpose();
  Eigen::Matrix4d n;
  n << s(0, 0) + s(1, 1) + s(2, 2), s(1, 2) - s(2, 1), s(2, 0) - s(0, 2), s(0, 1) - s(1, 0),  //
      s(1, 2) - s(2, 1), s(0, 0) - s(1, 1) - s(2, 2), s(0, 1) + s(1, 0), s(2, 0) + s(0, 2),    //
      s(2, 0) - s(0, 2), s(0, 1) + s(1, 0), -s(0, 0) + s(1, 1) - s(2, 2), s(1, 2) + s(2, 1),   //
      s(0, 1) - s(1, 0), s(2, 0) + s(0, 2), s(1, 2) + s(2, 1), -s(0, 0) - s(1, 1) + s(2, 2);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(n);
  const Eigen::Vector4d q = solver.eigenvectors().col(3);  // eigenvalues ascending
  const Eigen::Matrix3d rotation = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
  std::vector<double> distances;
  for (std::size_t i = 0; i < from.size(); ++i) {
    distances.push_back((rotation * (from[i] - mean_from) + mean_to - to[i]).norm());
  }
  return Rms(distances);
}

std::vector<Eigen::Vector3d> Positions(const std::vector<StampedPose>& poses) {
  std::vector<Eigen::Vector3d> out;
  for (const StampedPose& p : poses) out.push_back(p.world_T_body.translation());
  return out;
}

void ExpectNoError(const TrajectoryError3d& e, double metres, double degrees) {
  EXPECT_NEAR(e.ate_rmse_m, 0.0, metres);
  EXPECT_NEAR(e.ate_max_m, 0.0, metres);
  EXPECT_NEAR(e.rpe_frame.trans_rmse_m, 0.0, metres);
  EXPECT_NEAR(e.rpe_frame.rot_rmse_deg, 0.0, degrees);
  EXPECT_NEAR(e.rpe_delta.trans_rmse_m, 0.0, metres);
  EXPECT_NEAR(e.rpe_delta.rot_rmse_deg, 0.0, degrees);
}

TEST(InterpolatedPose, BetweenNeighboursAtTheirEndsAndNowhereElse) {
  const std::vector<StampedPose> poses = {
      {kStartNs, Pose({0, 0, 0}, 170 * kDeg, 0, 0)},
      {kStartNs + kStepNs, Pose({1, 2, -4}, -170 * kDeg, 0, 0)},  // 20 degrees on, across +-180
      {kStartNs + 5 * kStepNs, Pose({1, 2, -4}, 0, 0, 0)}};
  const auto middle = InterpolatedPose(poses, kStartNs + kStepNs / 2, 2 * kStepNs);
  ASSERT_TRUE(middle);
  EXPECT_TRUE(middle->translation().isApprox(Eigen::Vector3d(0.5, 1, -2), 1e-12)) << middle->translation();
  EXPECT_NEAR(AngleDeg(Pose({0, 0, 0}, 180 * kDeg, 0, 0).linear().transpose() * middle->linear()), 0.0, 1e-9);
  const auto quarter = InterpolatedPose(poses, kStartNs + kStepNs / 4, 2 * kStepNs);
  ASSERT_TRUE(quarter);
  EXPECT_NEAR(AngleDeg(poses[0].world_T_body.linear().transpose() * quarter->linear()), 5.0, 1e-9);
  // A pose's own time (within 2 us) needs no neighbour; the ends and a wide gap have none.
  EXPECT_TRUE(InterpolatedPose(poses, kStartNs - kNsPerUs, kStepNs));
  EXPECT_TRUE(InterpolatedPose(poses, kStartNs + 5 * kStepNs, kStepNs));
  EXPECT_FALSE(InterpolatedPose(poses, kStartNs - kNsPerMs, kStepNs));
  EXPECT_FALSE(InterpolatedPose(poses, kStartNs + 6 * kStepNs, 100 * kStepNs));
  EXPECT_FALSE(InterpolatedPose(poses, kStartNs + 2 * kStepNs, 3 * kStepNs));
  EXPECT_TRUE(InterpolatedPose(poses, kStartNs + 2 * kStepNs, 4 * kStepNs));
  EXPECT_FALSE(InterpolatedPose({}, kStartNs, kStepNs));
}

TEST(TrajectoryError3d, IdenticalTrajectoriesHaveNoError) {
  const auto truth = Truth();
  const auto e = EvaluateTrajectory3d(truth, truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_EQ(e->poses_matched, truth.size());
  EXPECT_EQ(e->poses_unmatched, 0u);
  EXPECT_EQ(e->rpe_frame.pairs, truth.size() - 1);
  EXPECT_EQ(e->rpe_delta.pairs, truth.size() - 100);  // 1 s at 100 Hz
  EXPECT_DOUBLE_EQ(e->rpe_delta_s, 1.0);
  ExpectNoError(*e, 1e-12, 1e-9);
  EXPECT_NEAR(e->ate_mean_m, 0.0, 1e-12);
  EXPECT_NEAR(e->ate_median_m, 0.0, 1e-12);
  EXPECT_TRUE(e->truth_T_estimate.isApprox(Eigen::Isometry3d::Identity(), 1e-12));
}

TEST(TrajectoryError3d, RigidlyMovedEstimateAlignsAndKeepsItsMotion) {
  // Random motions up to 1 km away and 180 degrees round, each applied to the estimate and,
  // the inverse case, to the truth.
  constexpr unsigned kSeed = 42;
  std::mt19937 rng(kSeed);
  const auto truth = Truth();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d motion = RandomMotion(rng, trial < 10 ? 10.0 : 1000.0);
    std::vector<StampedPose> moved = truth;
    for (StampedPose& p : moved) p.world_T_body = motion * p.world_T_body;
    SCOPED_TRACE(::testing::Message() << "seed " << kSeed << " trial " << trial);
    const auto e = EvaluateTrajectory3d(moved, truth);
    ASSERT_TRUE(e.ok()) << e.error().message;
    ExpectNoError(*e, 1e-8, 1e-6);
    EXPECT_TRUE(e->truth_T_estimate.isApprox(motion.inverse(), 1e-9))
        << "got\n" << e->truth_T_estimate.matrix() << "\nexpected\n" << motion.inverse().matrix();
    const auto inverse = EvaluateTrajectory3d(truth, moved);
    ASSERT_TRUE(inverse.ok());
    ExpectNoError(*inverse, 1e-8, 1e-6);
    EXPECT_TRUE(inverse->truth_T_estimate.isApprox(motion, 1e-9));
  }
}

TEST(TrajectoryError3d, ConstantPerFrameRotationErrorIsTheRpe) {
  // Each of the estimate's relative motions turned 1 degree more about the body's z axis.
  const auto truth = Truth();
  std::vector<StampedPose> estimate = {truth[0]};
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(1.0 * kDeg, Eigen::Vector3d::UnitZ()));
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Eigen::Isometry3d motion = truth[i - 1].world_T_body.inverse() * truth[i].world_T_body;
    estimate.push_back({truth[i].time_ns, estimate.back().world_T_body * motion * turn});
  }
  const auto e = EvaluateTrajectory3d(estimate, truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_NEAR(e->rpe_frame.rot_rmse_deg, 1.0, 1e-6);
  EXPECT_NEAR(e->rpe_frame.rot_median_deg, 1.0, 1e-6);
  EXPECT_NEAR(e->rpe_frame.trans_rmse_m, 0.0, 1e-9);
  EXPECT_GT(e->rpe_delta.rot_rmse_deg, 10.0);  // 100 frames of it, through the motion between
  EXPECT_GT(e->ate_rmse_m, 0.1);
}

TEST(TrajectoryError3d, PositionNoiseMatchesADirectComputation) {
  // Estimate positions off by Gaussian noise n_i: trans(E) = R_j^T (n_j - n_i), rotation 0,
  // and the ATE is Horn's fit of the noisy positions.
  constexpr unsigned kSeed = 42;
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 0.02);
  const auto truth = Truth();
  std::vector<StampedPose> estimate = truth;
  std::vector<Eigen::Vector3d> n;
  for (StampedPose& p : estimate) {
    n.push_back(Eigen::Vector3d{noise(rng), noise(rng), noise(rng)});  // braces: drawn in order
    p.world_T_body.translation() += n.back();
  }
  std::vector<double> unaligned, frame, delta;
  for (const Eigen::Vector3d& v : n) unaligned.push_back(v.norm());
  for (std::size_t i = 0; i + 1 < n.size(); ++i) frame.push_back((n[i + 1] - n[i]).norm());
  for (std::size_t i = 0; i + 100 < n.size(); ++i) delta.push_back((n[i + 100] - n[i]).norm());
  const double ate = HornAteRmse(Positions(estimate), Positions(truth));

  const auto e = EvaluateTrajectory3d(estimate, truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  EXPECT_NEAR(e->rpe_frame.trans_rmse_m, Rms(frame), 1e-12);
  EXPECT_NEAR(e->rpe_frame.trans_median_m, NearestRankMedian(frame), 1e-12);
  EXPECT_NEAR(e->rpe_delta.trans_rmse_m, Rms(delta), 1e-12);
  EXPECT_NEAR(e->rpe_delta.trans_median_m, NearestRankMedian(delta), 1e-12);
  EXPECT_NEAR(e->rpe_frame.rot_rmse_deg, 0.0, 1e-6);
  EXPECT_NEAR(e->ate_rmse_m, ate, 1e-9);
  EXPECT_LE(e->ate_rmse_m, Rms(unaligned));  // the best fit is no worse than none
  EXPECT_LE(e->ate_median_m, e->ate_max_m);
  EXPECT_LE(e->ate_mean_m, e->ate_rmse_m);
  std::printf("seed %u: ATE %.6f m (Horn %.6f), RPE frame %.6f m (direct %.6f)\n", kSeed, e->ate_rmse_m, ate,
              e->rpe_frame.trans_rmse_m, Rms(frame));
}

TEST(TrajectoryError3d, DeltaPairsTakeTheFirstPoseAtLeastDeltaLater) {
  // At 0, 0.45, 0.9, 1.5, 2.4 s: pairs (0, 3), (1, 3), (2, 4); nearest in time would pair 0
  // with 2. Pose 2 is 0.1 m off, so one pair of three sees it.
  const auto truth = Truth(300);
  std::vector<StampedPose> estimate;
  for (const int index : {0, 45, 90, 150, 240}) estimate.push_back(truth[static_cast<std::size_t>(index)]);
  estimate[2].world_T_body.translation() += Eigen::Vector3d(0.0, 0.1, 0.0);
  const auto e = EvaluateTrajectory3d(estimate, truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_EQ(e->rpe_delta.pairs, 3u);
  EXPECT_NEAR(e->rpe_delta.trans_rmse_m, std::sqrt(0.01 / 3.0), 1e-12);
  EXPECT_NEAR(e->rpe_delta.trans_median_m, 0.0, 1e-12);
  EXPECT_EQ(e->rpe_frame.pairs, 4u);
  EXPECT_NEAR(e->rpe_frame.trans_rmse_m, std::sqrt(0.02 / 4.0), 1e-12);  // (1, 2) and (2, 3)

  TrajectoryError3dOptions options;
  options.rpe_delta_s = 0.5;  // (0, 2), (1, 3), (2, 3), (3, 4)
  const auto half = EvaluateTrajectory3d(estimate, truth, options);
  ASSERT_TRUE(half.ok());
  EXPECT_EQ(half->rpe_delta.pairs, 4u);
  EXPECT_DOUBLE_EQ(half->rpe_delta_s, 0.5);
  EXPECT_NEAR(half->rpe_delta.trans_rmse_m, std::sqrt(0.02 / 4.0), 1e-12);
}

TEST(TrajectoryError3d, PosesTheTruthDoesNotCoverAreCountedNotScored) {
  auto truth = Truth(300);
  truth.erase(truth.begin() + 100, truth.begin() + 110);  // a 0.11 s gap in the truth
  std::vector<StampedPose> estimate = Truth(400);           // and 1 s beyond its end
  const auto e = EvaluateTrajectory3d(estimate, truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_EQ(e->poses_unmatched, 100u + 10u);
  EXPECT_EQ(e->poses_matched, 290u);
  EXPECT_EQ(e->rpe_frame.pairs, 290u - 2u);  // none across the gap
  ExpectNoError(*e, 1e-12, 1e-9);

  TrajectoryError3dOptions wide;
  wide.max_gap_s = 0.2;  // interpolates across the gap
  const auto across = EvaluateTrajectory3d(estimate, truth, wide);
  ASSERT_TRUE(across.ok());
  EXPECT_EQ(across->poses_matched, 300u);
  EXPECT_EQ(across->rpe_frame.pairs, 299u);
  EXPECT_GT(across->ate_max_m, 1e-6);  // a chord across the curve

  std::vector<StampedPose> later = estimate;
  for (StampedPose& p : later) p.time_ns += 100 * kNsPerSecond;
  const auto none = EvaluateTrajectory3d(later, truth);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("none of the estimate's 400 poses"), std::string::npos) << none.error().message;
  EXPECT_FALSE(EvaluateTrajectory3d({}, truth).ok());
}

// The truth at `time_ns` by a linear scan, the rotation by the exponential map of the relative
// rotation (the library slerps quaternions), neighbours at most `max_gap_ns` apart.
std::optional<Eigen::Isometry3d> TruthByScan(const std::vector<StampedPose>& truth, TimeNs time_ns,
                                             TimeNs max_gap_ns) {
  for (std::size_t b = 1; b < truth.size(); ++b) {
    const StampedPose& p0 = truth[b - 1];
    const StampedPose& p1 = truth[b];
    if (p0.time_ns == time_ns) return p0.world_T_body;
    if (p1.time_ns == time_ns) return p1.world_T_body;
    if (p1.time_ns < time_ns || p0.time_ns > time_ns) continue;
    if (p1.time_ns - p0.time_ns > max_gap_ns) return std::nullopt;
    const double f = static_cast<double>(time_ns - p0.time_ns) / static_cast<double>(p1.time_ns - p0.time_ns);
    const Eigen::Isometry3d relative = p0.world_T_body.inverse() * p1.world_T_body;
    const Eigen::AngleAxisd turn(relative.linear());
    Eigen::Isometry3d q = p0.world_T_body;
    q.linear() = q.linear() * Eigen::AngleAxisd(f * turn.angle(), turn.axis()).toRotationMatrix();
    q.translation() += f * (p1.world_T_body.translation() - p0.world_T_body.translation());
    return q;
  }
  return std::nullopt;
}

// What the library should find for `estimate` against `truth` with TruthByScan: Eq. 1 per
// frame written out, and the matched positions for Horn.
struct DirectEvaluation {
  std::vector<double> trans_m, rot_deg;
  std::vector<Eigen::Vector3d> from, to;
};

DirectEvaluation EvaluateDirectly(const std::vector<StampedPose>& estimate, const std::vector<StampedPose>& truth) {
  std::vector<std::optional<Eigen::Isometry3d>> at;
  for (const StampedPose& p : estimate) at.push_back(TruthByScan(truth, p.time_ns, 20 * kNsPerMs));
  DirectEvaluation out;
  for (std::size_t k = 0; k < estimate.size(); ++k) {
    if (!at[k]) continue;
    out.from.push_back(estimate[k].world_T_body.translation());
    out.to.push_back(at[k]->translation());
    if (k + 1 == estimate.size() || !at[k + 1]) continue;
    const Eigen::Isometry3d error = (at[k]->inverse() * *at[k + 1]).inverse() *
                                    (estimate[k].world_T_body.inverse() * estimate[k + 1].world_T_body);
    out.trans_m.push_back(error.translation().norm());
    out.rot_deg.push_back(AngleDeg(error.linear()));
  }
  return out;
}

// The TUM RGB-D fr1/rpy truth (100 Hz mocap, 2742 poses, gaps up to 0.13 s) against itself,
// then against itself 10 ms late: the errors of that lag, computed here independently.
TEST(TrajectoryError3d, TumFr1RpyTruthAgainstItselfAndLate) {
  FLAT2D_REQUIRE_DATA(path, "depth/tum_rgbd_fr1_rpy_first200/groundtruth.txt");
  const auto truth = hal::trajectory::ReadTum(path);
  ASSERT_TRUE(truth.ok()) << truth.error().message;
  const auto same = EvaluateTrajectory3d(*truth, *truth);
  ASSERT_TRUE(same.ok()) << same.error().message;
  EXPECT_EQ(same->poses_matched, truth->size());
  ExpectNoError(*same, 1e-9, 1e-6);

  std::vector<StampedPose> late = *truth;
  for (StampedPose& p : late) p.time_ns += 10 * kNsPerMs;
  const DirectEvaluation direct = EvaluateDirectly(late, *truth);
  const auto e = EvaluateTrajectory3d(late, *truth);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_EQ(e->poses_matched, direct.from.size());
  EXPECT_EQ(e->poses_matched, truth->size() - 8);  // the last pose, and 7 in gaps over 0.02 s
  EXPECT_EQ(e->rpe_frame.pairs, direct.trans_m.size());
  EXPECT_NEAR(e->rpe_frame.trans_rmse_m, Rms(direct.trans_m), 1e-9);
  EXPECT_NEAR(e->rpe_frame.rot_rmse_deg, Rms(direct.rot_deg), 1e-6);
  EXPECT_NEAR(e->rpe_frame.trans_median_m, NearestRankMedian(direct.trans_m), 1e-9);
  EXPECT_NEAR(e->rpe_frame.rot_median_deg, NearestRankMedian(direct.rot_deg), 1e-6);
  EXPECT_NEAR(e->ate_rmse_m, HornAteRmse(direct.from, direct.to), 1e-9);
  EXPECT_GT(e->rpe_frame.rot_rmse_deg, 0.05);  // fr1/rpy turns fast: 10 ms shows
  std::printf("fr1/rpy truth 10 ms late: %zu of %zu poses matched; ATE %.6f m (Horn %.6f); RPE per frame "
              "%.6f m, %.6f deg (direct %.6f m, %.6f deg); over 1 s %.6f m, %.6f deg (%zu pairs)\n",
              e->poses_matched, late.size(), e->ate_rmse_m, HornAteRmse(direct.from, direct.to),
              e->rpe_frame.trans_rmse_m, e->rpe_frame.rot_rmse_deg, Rms(direct.trans_m), Rms(direct.rot_deg),
              e->rpe_delta.trans_rmse_m, e->rpe_delta.rot_rmse_deg, e->rpe_delta.pairs);
}

}  // namespace
}  // namespace flat2d::localization::evaluation
