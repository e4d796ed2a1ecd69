#include "localization/loops/robust_closures.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::localization::loops {
namespace {

using graph::Matrix6d;
using graph::Se3BetweenFactor;
using graph::Se3PoseGraph;

// Two laps of a circle of radius 20 m, a local map every 2 m (63 per lap), 5 cm high waves.
std::vector<Eigen::Isometry3d> TwoLaps() {
  constexpr int kPerLap = 63;
  std::vector<Eigen::Isometry3d> truth;
  for (int i = 0; i < 2 * kPerLap; ++i) {
    const double angle = 2.0 * M_PI * i / kPerLap;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(20.0 * std::sin(angle), 20.0 * (1.0 - std::cos(angle)), 0.05 * std::sin(3 * angle));
    pose.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    truth.push_back(pose);
  }
  return truth;
}

Matrix6d Information(double sigma_m, double sigma_rad) {
  Matrix6d information = Matrix6d::Zero();
  information.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / (sigma_m * sigma_m));
  information.bottomRightCorner<3, 3>().diagonal().setConstant(4.0 / (sigma_rad * sigma_rad));
  return information;
}

Eigen::Isometry3d Noisy(const Eigen::Isometry3d& pose, double sigma_m, double sigma_rad, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d noisy = pose;
  // Braces: the draws are made in order (a call's arguments have none).
  noisy.translation() += sigma_m * Eigen::Vector3d{n(rng), n(rng), n(rng)};
  const Eigen::AngleAxisd turn{sigma_rad * n(rng), Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized()};
  noisy.linear() = noisy.linear() * turn.toRotationMatrix();
  return noisy;
}

struct Scenario {
  std::vector<Eigen::Isometry3d> truth = TwoLaps();
  Se3PoseGraph graph;
  std::vector<std::size_t> true_closures, false_closures;
};

// A chain whose odometry turns 0.05 deg too far per map (within its sigma; 2-3 m off after
// two laps), closures
// of the second lap to the first, and `false_count` closures that claim two distant maps
// are one place.
// `closures_at`: the second-lap maps that get a closure (default: every third from the 5th);
// `bias_deg`: the odometry's turn too far per map.
Scenario MakeScenario(int false_count, std::uint32_t seed, std::vector<int> closures_at = {}, double bias_deg = 0.05) {
  Scenario s;
  std::mt19937 rng(seed);
  const int n = static_cast<int>(s.truth.size());
  const Eigen::Isometry3d bias(Eigen::AngleAxisd(bias_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  Eigen::Isometry3d estimate = s.truth.front();
  s.graph.AddNode(estimate);
  for (int i = 1; i < n; ++i) {
    Se3BetweenFactor f;
    f.from = static_cast<std::size_t>(i - 1);
    f.to = static_cast<std::size_t>(i);
    f.measurement = Noisy(s.truth[f.from].inverse() * s.truth[f.to], 0.01, 0.001, rng) * bias;
    f.information = Information(0.02, 0.002);
    estimate = estimate * f.measurement;
    s.graph.AddNode(estimate);
    s.graph.betweens.push_back(f);
  }
  const int per_lap = n / 2;
  if (closures_at.empty()) {
    for (int i = per_lap + 5; i < n; i += 3) closures_at.push_back(i);
  }
  for (const int i : closures_at) {
    Se3BetweenFactor f;
    f.from = static_cast<std::size_t>(i - per_lap);
    f.to = static_cast<std::size_t>(i);
    f.measurement = Noisy(s.truth[f.from].inverse() * s.truth[f.to], 0.02, 0.002, rng);
    f.information = Information(0.05, 0.005);
    s.true_closures.push_back(s.graph.betweens.size());
    s.graph.betweens.push_back(f);
  }
  std::uniform_int_distribution<int> map(0, n - 1);
  while (static_cast<int>(s.false_closures.size()) < false_count) {
    const int a = map(rng), b = map(rng);
    if (b - a < 10 || (s.truth[static_cast<std::size_t>(a)].translation() - s.truth[static_cast<std::size_t>(b)].translation()).norm() < 10.0) continue;
    Se3BetweenFactor f;
    f.from = static_cast<std::size_t>(a);
    f.to = static_cast<std::size_t>(b);
    f.information = Information(0.05, 0.005);  // identity measurement: "the same place"
    s.false_closures.push_back(s.graph.betweens.size());
    s.graph.betweens.push_back(f);
  }
  return s;
}

// Aligned at the first node, which the optimizer holds.
double RmsError(const Se3PoseGraph& graph, const std::vector<Eigen::Isometry3d>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    sum += (graph.nodes[i].estimate.translation() - truth[i].translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(truth.size()));
}

// The RMS distance between two solutions of one graph's nodes.
double RmsDifference(const Se3PoseGraph& a, const Se3PoseGraph& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    sum += (a.nodes[i].estimate.translation() - b.nodes[i].estimate.translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(a.nodes.size()));
}

std::vector<std::size_t> All(const Scenario& s) {
  std::vector<std::size_t> closures = s.true_closures;
  closures.insert(closures.end(), s.false_closures.begin(), s.false_closures.end());
  return closures;
}

TEST(RobustClosures, ConsistentClosuresAreAllKeptAndCloseTheLoop) {
  Scenario s = MakeScenario(0, 1);
  const double open_loop = RmsError(s.graph, s.truth);
  const RobustClosureResult r = OptimizeWithRobustClosures(s.graph, s.true_closures, RobustClosureOptions{});
  // The bias stays in the turns between closures; the loop's error is what closes.
  EXPECT_GT(open_loop, 1.0);
  EXPECT_LT(RmsError(s.graph, s.truth), 0.25 * open_loop) << open_loop;
  for (std::size_t c = 0; c < s.true_closures.size(); ++c) EXPECT_TRUE(r.kept[c]) << c;
  EXPECT_TRUE(r.converged);
}

// The acceptance test's 20 % false closures (here past the validation): each claims two
// maps at least 10 m apart are one place. Over seeds, every false one is dropped, every
// true one kept, and the solution is within 1 cm (RMS) of the one without them.
TEST(RobustClosures, TwentyPercentFalseClosuresAreDroppedAndChangeNothing) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    Scenario clean = MakeScenario(0, seed);
    (void)OptimizeWithRobustClosures(clean.graph, clean.true_closures, RobustClosureOptions{});
    const int false_count = static_cast<int>(clean.true_closures.size()) / 4;  // 20 % of all
    Scenario s = MakeScenario(false_count, seed);
    const std::vector<std::size_t> closures = All(s);
    const RobustClosureResult r = OptimizeWithRobustClosures(s.graph, closures, RobustClosureOptions{});
    for (std::size_t c = 0; c < closures.size(); ++c) {
      const bool is_false = c >= s.true_closures.size();
      EXPECT_EQ(r.kept[c], !is_false) << "seed " << seed << " closure " << c << " scale " << r.scales[c];
    }
    EXPECT_LT(RmsDifference(s.graph, clean.graph), 0.01) << "seed " << seed;
  }
}

// Without the kernel (every scale held at 1) the same false closures bend the map: what
// the kernel is there for.
TEST(RobustClosures, WithoutTheKernelFalseClosuresBendTheMap) {
  Scenario s = MakeScenario(5, 1);
  RobustClosureOptions plain;
  plain.phi = 1e12;
  (void)OptimizeWithRobustClosures(s.graph, All(s), plain);
  EXPECT_GT(RmsError(s.graph, s.truth), 0.5);
}

// A chain broken as flat2d-map build --mode catacomb --break-chain breaks it (thesis Fig.
// 6.7): one tie, the odometry's guess across a failed registration (0.2 m, 0.02 rad), is
// 1 m and 5 deg wrong, and the only closures are three at one place of the second lap (the
// office's revisit: maps 40-41 seen again as 81-82). Held at full weight, the tie keeps part
// of its error and bends the lap; judged against the kept closures (JudgeWeakTies) it gives
// way and the step across the break comes near the truth's. (The chain is unbiased here: a
// discounted tie takes more of its loop's misclosure, the chain's drift with the break. On
// the simulated office the tie is overruled: docs/benchmarks.md.)
TEST(RobustClosures, ABrokenWeakTieGivesWayToTheKeptClosures) {
  constexpr std::size_t kBreak = 40;  // the tie from map 40 to 41, inside the loop the closures close
  const std::vector<int> closures_at{83, 84, 85};  // maps 20-22 seen again
  auto broken = [&] {
    Scenario s = MakeScenario(0, 3, closures_at, 0.0);
    Se3BetweenFactor& tie = s.graph.betweens[kBreak];
    Eigen::Isometry3d error(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    error.translation() = Eigen::Vector3d(0.0, 1.0, 0.0);
    tie.measurement = tie.measurement * error;
    tie.information = Information(0.2, 0.02);
    for (std::size_t i = kBreak + 1; i < s.graph.nodes.size(); ++i) {
      s.graph.nodes[i].estimate = s.graph.nodes[i - 1].estimate * s.graph.betweens[i - 1].measurement;
    }
    return s;
  };
  Scenario kept = broken();
  (void)OptimizeWithRobustClosures(kept.graph, kept.true_closures, RobustClosureOptions{});
  Scenario judged = broken();
  RobustClosureResult r = OptimizeWithRobustClosures(judged.graph, judged.true_closures, RobustClosureOptions{});
  for (std::size_t c = 0; c < judged.true_closures.size(); ++c) EXPECT_TRUE(r.kept[c]) << c;
  const std::vector<std::size_t> ties{kBreak};
  const int rounds = r.rounds;
  const std::vector<double> tie_scales =
      JudgeWeakTies(judged.graph, ties, judged.true_closures, r.kept, RobustClosureOptions{}, r);
  ASSERT_EQ(tie_scales.size(), 1u);
  EXPECT_LT(tie_scales[0], 0.8);  // discounted
  EXPECT_GT(r.rounds, rounds);
  // The step across the break against the truth's: what the repair is about.
  auto step_error_deg = [&](const Scenario& s) {
    const auto& nodes = s.graph.nodes;
    const Eigen::Isometry3d error = (s.truth[kBreak].inverse() * s.truth[kBreak + 1]).inverse() *
                                    (nodes[kBreak].estimate.inverse() * nodes[kBreak + 1].estimate);
    return Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI;
  };
  const double kept_rms = RmsError(kept.graph, kept.truth), judged_rms = RmsError(judged.graph, judged.truth);
  std::printf("step across the break: %.2f deg at full weight, %.2f deg judged (scale %.2f); RMS %.3f m and %.3f m\n",
              step_error_deg(kept), step_error_deg(judged), tie_scales[0], kept_rms, judged_rms);
  EXPECT_GT(step_error_deg(kept), 1.0);
  EXPECT_LT(step_error_deg(judged), 0.6 * step_error_deg(kept));
  EXPECT_LT(judged_rms, 0.9 * kept_rms);
}

// The campus case: a correct weak tie and 20 % false closures. The false ones are dropped
// first; judged against the kept ones the tie keeps its weight, and the solution is the
// clean one. (Why first: judged in one solve with the closures, the simulated campus with
// 20 % injected false candidates tore open at 6 of its 9 failure ties and ended 144 m off,
// docs/benchmarks.md. Here the laps' dense true closures would hold either way.)
TEST(RobustClosures, FalseClosuresCannotOverruleACorrectWeakTie) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    constexpr std::size_t kWeak = 70;
    Scenario clean = MakeScenario(0, seed);
    clean.graph.betweens[kWeak].information = Information(0.2, 0.02);
    (void)OptimizeWithRobustClosures(clean.graph, clean.true_closures, RobustClosureOptions{});
    Scenario s = MakeScenario(static_cast<int>(clean.true_closures.size()) / 4, seed);
    s.graph.betweens[kWeak].information = Information(0.2, 0.02);
    const std::vector<std::size_t> closures = All(s);
    RobustClosureResult r = OptimizeWithRobustClosures(s.graph, closures, RobustClosureOptions{});
    const std::vector<std::size_t> ties{kWeak};
    const std::vector<double> tie_scales = JudgeWeakTies(s.graph, ties, closures, r.kept, RobustClosureOptions{}, r);
    EXPECT_GE(tie_scales[0], 0.5) << "seed " << seed;
    for (std::size_t c = s.true_closures.size(); c < closures.size(); ++c) EXPECT_FALSE(r.kept[c]) << "seed " << seed;
    EXPECT_LT(RmsDifference(s.graph, clean.graph), 0.01) << "seed " << seed;
  }
}

// Without a kept closure the ties are not judged: no solve, full weight.
TEST(RobustClosures, WeakTiesWithoutKeptClosuresKeepTheirWeight) {
  Scenario s = MakeScenario(0, 1);
  RobustClosureResult r;
  const std::vector<std::size_t> ties{10, 20};
  const std::vector<std::size_t> closures = s.true_closures;
  const std::vector<double> scales = JudgeWeakTies(s.graph, ties, closures, std::vector<bool>(closures.size(), false),
                                                   RobustClosureOptions{}, r);
  EXPECT_EQ(scales, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(r.rounds, 0);
}

}  // namespace
}  // namespace flat2d::localization::loops
