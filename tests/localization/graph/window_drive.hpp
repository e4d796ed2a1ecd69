// A synthetic drive for the sliding-window tests and benchmark: a smooth path of true
// poses, noisy odometry between consecutive poses with known sigma, noisy global matches
// every few nodes, some replaced by gross outliers. Seeded, so every run is the same.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "localization/graph/sliding_window.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::graph::testing {

// Unoptimized (Debug, sanitizer) builds run Eigen's 3x3 algebra ~100x slower; there the
// long drives shrink to this fraction: memory and UB checks don't need 2000 nodes.
#ifdef NDEBUG
inline constexpr int kDriveDivisor = 1;
#else
inline constexpr int kDriveDivisor = 8;
#endif

struct DriveOptions {
  int nodes = 2000;
  double step_m = 1.0;               // distance between nodes
  bool straight = false;             // heading constant (0) instead of a weaving path
  double odometry_sigma_xy = 0.02;   // m, per step
  double odometry_sigma_theta = 0.002;  // rad, per step
  int match_every = 3;               // 0: no matches
  double match_sigma_xy = 0.05;
  double match_sigma_theta = 0.005;
  int outlier_every = 0;             // every k-th match is a gross outlier; 0: none
  std::uint32_t seed = 42;
};

struct DriveStep {
  Se2 truth;          // global_T_vehicle
  Se2 odometry;       // previous_T_this, noisy (identity for the first node)
  bool has_match = false;
  bool outlier = false;
  Se2 match;          // global_T_vehicle, noisy or gross
};

inline Eigen::Matrix3d InformationOf(double sigma_xy, double sigma_theta) {
  return Eigen::Vector3d(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy),
                         1.0 / (sigma_theta * sigma_theta))
      .asDiagonal();
}

inline Eigen::Matrix3d OdometryInformation(const DriveOptions& o) {
  return InformationOf(o.odometry_sigma_xy, o.odometry_sigma_theta);
}
inline Eigen::Matrix3d MatchInformation(const DriveOptions& o) {
  return InformationOf(o.match_sigma_xy, o.match_sigma_theta);
}

// Weak enough to tell a 20-sigma outlier from a match (F5: the switch is near 7 sigma).
inline NullHypothesis TestNullHypothesis() { return {.weight = 0.1, .information_scale = 1e-6}; }

inline Se2 AddNoise(const Se2& pose, double sigma_xy, double sigma_theta, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double dx = sigma_xy * n(rng);
  const double dy = sigma_xy * n(rng);
  const double dt = sigma_theta * n(rng);
  return Se2(pose.x() + dx, pose.y() + dy, pose.theta() + dt);
}

inline std::vector<DriveStep> MakeDrive(const DriveOptions& o) {
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> gross(-1.0, 1.0);
  std::vector<DriveStep> drive(static_cast<std::size_t>(o.nodes));
  Se2 truth(10.0, -5.0, 0.3 * (o.straight ? 0.0 : 1.0));
  int matches = 0;
  for (int k = 0; k < o.nodes; ++k) {
    DriveStep& step = drive[static_cast<std::size_t>(k)];
    if (k > 0) {
      const double turn = o.straight ? 0.0 : 0.04 * std::sin(0.013 * k) + 0.01 * std::cos(0.05 * k);
      const Se2 motion = Arc(o.step_m, turn);
      truth = truth * motion;
      step.odometry = AddNoise(motion, o.odometry_sigma_xy, o.odometry_sigma_theta, rng);
    }
    step.truth = truth;
    if (o.match_every > 0 && k % o.match_every == 0) {
      step.has_match = true;
      ++matches;
      step.outlier = o.outlier_every > 0 && matches % o.outlier_every == 0;
      // Braces: the draws are made in order (a call's arguments have none).
      step.match = step.outlier
                       ? Se2{truth.x() + 2.0 + 8.0 * std::abs(gross(rng)), truth.y() + 5.0 * gross(rng),
                             truth.theta() + 0.5 * gross(rng)}
                       : AddNoise(truth, o.match_sigma_xy, o.match_sigma_theta, rng);
    }
  }
  return drive;
}

// Feeds step k into the window: a node predicted from the previous estimate and the
// odometry, the odometry factor, the match; the first node gets a prior at the truth.
inline NodeId FeedStep(SlidingWindowGraph& window, const std::vector<DriveStep>& drive, int k,
                       const DriveOptions& o) {
  const DriveStep& step = drive[static_cast<std::size_t>(k)];
  const TimeNs time = 100'000'000LL * (k + 1);
  NodeId id = 0;
  if (k == 0) {
    id = window.AddNode(time, step.truth).value();
    (void)window.AddPrior(id, step.truth, InformationOf(0.1, 0.01));
  } else {
    const Se2 predicted = *window.Estimate(window.newest_id()) * step.odometry;
    const NodeId previous = window.newest_id();
    id = window.AddNode(time, predicted).value();
    (void)window.AddOdometry(previous, id, step.odometry, OdometryInformation(o));
  }
  if (step.has_match) {
    (void)window.AddMatch(id, step.match, MatchInformation(o), TestNullHypothesis());
  }
  return id;
}

}  // namespace flat2d::localization::graph::testing
