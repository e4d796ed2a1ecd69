#include "localization/calibration/ground_plane.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>

#include "hal/common/angles.hpp"

namespace flat2d::localization::calibration {
namespace {

// The candidates: within the range band and more than half the guessed height below.
std::vector<Eigen::Vector3d> Candidates(std::span<const Eigen::Vector3f> points, const Eigen::Vector3d& up, double guessed_height_m,
                                        const GroundPlaneOptions& options) {
  std::vector<Eigen::Vector3d> candidates;
  const double min2 = options.min_range_m * options.min_range_m, max2 = options.max_range_m * options.max_range_m;
  for (const Eigen::Vector3f& pf : points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double r2 = p.squaredNorm();
    if (r2 >= min2 && r2 <= max2 && p.dot(up) < -0.5 * guessed_height_m) candidates.push_back(p);
  }
  return candidates;
}

// Plane n.x = d with |n| = 1 through three points; none when they are (nearly) collinear.
std::optional<std::pair<Eigen::Vector3d, double>> PlaneThrough(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  if (n.norm() < 1e-6) return std::nullopt;
  const Eigen::Vector3d unit = n.normalized();
  return std::make_pair(unit, unit.dot(a));
}

int CountInliers(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double d, double distance) {
  int count = 0;
  for (const Eigen::Vector3d& p : points) count += std::abs(n.dot(p) - d) <= distance ? 1 : 0;
  return count;
}

// Least squares plane of the inliers of (n, d): the centroid and the smallest eigenvector.
GroundPlane Refine(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double d, double distance, const Eigen::Vector3d& up) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  int count = 0;
  for (const Eigen::Vector3d& p : points) {
    if (std::abs(n.dot(p) - d) > distance) continue;
    sum += p;
    outer += p * p.transpose();
    ++count;
  }
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d covariance = outer / count - mean * mean.transpose();
  Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  if (normal.dot(up) < 0.0) normal = -normal;
  return {normal, -normal.dot(mean), count};
}

}  // namespace

std::optional<GroundPlane> FitGroundPlane(std::span<const Eigen::Vector3f> points, const Eigen::Vector3d& up, double guessed_height_m,
                                          const GroundPlaneOptions& options) {
  const std::vector<Eigen::Vector3d> candidates = Candidates(points, up, guessed_height_m, options);
  if (std::ssize(candidates) < options.min_inliers) return std::nullopt;
  std::mt19937 random(options.seed);
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  const double min_cos = std::cos(options.max_tilt_deg * kDegToRad);
  int best = 0;
  Eigen::Vector3d best_n = up;
  double best_d = 0.0;
  for (int i = 0; i < options.ransac_iterations; ++i) {
    // Drawn one by one: as arguments of one call the three draws have no order, and each
    // compiler would take another sample from the same seed.
    const std::size_t a = pick(random), b = pick(random), c = pick(random);
    const auto plane = PlaneThrough(candidates[a], candidates[b], candidates[c]);
    if (!plane || std::abs(plane->first.dot(up)) < min_cos) continue;
    const int inliers = CountInliers(candidates, plane->first, plane->second, options.inlier_distance_m);
    if (inliers > best) {
      best = inliers;
      best_n = plane->first;
      best_d = plane->second;
    }
  }
  if (best < options.min_inliers) return std::nullopt;
  GroundPlane ground = Refine(candidates, best_n, best_d, options.inlier_distance_m, up);
  if (ground.normal.dot(up) < min_cos || !(ground.height_m > 0.0)) return std::nullopt;
  return ground;
}

Eigen::Vector2d RollPitchOf(const Eigen::Vector3d& normal) {
  // R^T z = (-sin p, cos p sin r, cos p cos r).
  return {std::atan2(normal.y(), normal.z()), std::asin(std::clamp(-normal.x(), -1.0, 1.0))};
}

}  // namespace flat2d::localization::calibration
