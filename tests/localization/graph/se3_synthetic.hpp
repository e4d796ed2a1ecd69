// Random SE(3) poses and a synthetic pose graph with known truth for the SE(3) tests: a
// corkscrew of poses (each step 1 m forward, turning about a random axis) with odometry
// edges and loop closures between laps, measurements exact or with Gaussian noise.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "localization/graph/se3_factors.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph::synthetic {

// A rotation of angle below `max_angle` about a uniformly random axis.
inline Eigen::Matrix3d RandomRotation(std::mt19937& rng, double max_angle) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, max_angle);
  // Braces: the draws are made in order (a call's arguments have none).
  const Eigen::Vector3d axis = Eigen::Vector3d{gauss(rng), gauss(rng), gauss(rng)}.normalized();
  return ExpSo3(angle(rng) * axis);
}

inline Eigen::Isometry3d RandomPose(std::mt19937& rng, double extent, double max_angle) {
  std::uniform_real_distribution<double> position(-extent, extent);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = RandomRotation(rng, max_angle);
  pose.translation() = Eigen::Vector3d{position(rng), position(rng), position(rng)};
  return pose;
}

// An anisotropic, correlated information matrix (translation block first), as in the files.
inline Matrix6d TestInformation() {
  Matrix6d information = Matrix6d::Zero();
  information.topLeftCorner<3, 3>() << 100.0, 5.0, 0.0, 5.0, 80.0, 2.0, 0.0, 2.0, 50.0;
  information.bottomRightCorner<3, 3>() << 400.0, 10.0, 0.0, 10.0, 300.0, 0.0, 0.0, 0.0, 500.0;
  information(0, 3) = information(3, 0) = 3.0;
  return information;
}

struct Se3Synthetic {
  Se3PoseGraph graph;  // estimates at the truth; measurements exact or noisy
  std::vector<Eigen::Isometry3d> truth;
};

// Two laps of `per_lap` poses; loop closures from every third pose of lap 1 to lap 2.
inline Se3Synthetic Corkscrew(unsigned seed, int per_lap, double noise) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Se3Synthetic s;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.translation() = Eigen::Vector3d(1.0, 0.0, 0.1);
  step.linear() = ExpSo3(Eigen::Vector3d(0.1, 0.05, 2.0 * std::numbers::pi / per_lap));
  for (int k = 0; k < 2 * per_lap; ++k) {
    s.truth.push_back(pose);
    s.graph.AddNode(pose);
    pose = pose * step;
  }
  auto add_edge = [&](std::size_t i, std::size_t j) {
    Vector6d delta;
    for (int c = 0; c < 6; ++c) delta[c] = noise * (c < 3 ? 1.0 : 0.1) * gauss(rng);
    const Eigen::Isometry3d z = Retract(s.truth[i].inverse() * s.truth[j], delta);
    s.graph.betweens.push_back({i, j, z, TestInformation()});
  };
  for (std::size_t k = 1; k < s.truth.size(); ++k) add_edge(k - 1, k);
  for (std::size_t k = 0; k < static_cast<std::size_t>(per_lap); k += 3) add_edge(k, k + per_lap);
  return s;
}

}  // namespace flat2d::localization::graph::synthetic
