#include "localization/matching/score_surface.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace flat2d::localization {
namespace {

struct Normal {
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  double cost = 0.0;
};

// Gauss-Newton normal equations of r_i = 1 - T(pose p_i) / kMaxCellScore.
Normal NormalEquations(const ScoreTable& table, std::span<const Eigen::Vector2d> points,
                       const Se2& pose) {
  const GridGeometry& geometry = table.geometry();
  const Eigen::Matrix2d rotation = pose.Rotation();
  Normal normal;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d rotated = rotation * p;
    const Eigen::Vector2d cell = (rotated + pose.translation() - geometry.origin) / geometry.resolution;
    const Eigen::Vector3d value = table.InterpolateWithGradient(cell.x(), cell.y());
    const double residual = 1.0 - value.x() / kMaxCellScore;
    // d cell / d (x, y, theta) = [I, (-rotated.y, rotated.x)] / resolution.
    const Eigen::Vector2d d_cell = value.tail<2>() / (-kMaxCellScore * geometry.resolution);
    const Eigen::Vector3d jacobian(d_cell.x(), d_cell.y(),
                                   d_cell.x() * -rotated.y() + d_cell.y() * rotated.x());
    normal.hessian += jacobian * jacobian.transpose();
    normal.gradient += jacobian * residual;
    normal.cost += residual * residual;
  }
  return normal;
}

}  // namespace

Se2 RefineContinuous(const ScoreTable& table, std::span<const Eigen::Vector2d> points,
                     const Se2& start, int iterations, double max_shift, double max_turn) {
  Se2 pose = start;
  Normal normal = NormalEquations(table, points, pose);
  double lambda = 1.0e-3;
  for (int i = 0; i < iterations; ++i) {
    Eigen::Matrix3d damped = normal.hessian;
    damped.diagonal() *= 1.0 + lambda;
    damped.diagonal().array() += 1.0e-9;
    const Eigen::Vector3d step = damped.ldlt().solve(-normal.gradient);
    const Se2 candidate(pose.x() + step.x(), pose.y() + step.y(), pose.theta() + step.z());
    const bool inside = (candidate.translation() - start.translation()).norm() <= max_shift &&
                        std::abs(NormalizeAngle(candidate.theta() - start.theta())) <= max_turn;
    const Normal next = NormalEquations(table, points, candidate);
    if (inside && step.allFinite() && next.cost < normal.cost) {
      pose = candidate;
      normal = next;
      lambda = std::max(lambda * 0.1, 1.0e-6);
    } else {
      lambda *= 10.0;
    }
  }
  return pose;
}

double ContinuousScore(const ScoreTable& table, std::span<const Eigen::Vector2d> points,
                       const Se2& map_T_vehicle) {
  if (points.empty()) return 0.0;
  const GridGeometry& geometry = table.geometry();
  const Eigen::Matrix2d rotation = map_T_vehicle.Rotation() / geometry.resolution;
  const Eigen::Vector2d start = (map_T_vehicle.translation() - geometry.origin) / geometry.resolution;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d cell = rotation * p + start;
    sum += table.Interpolate(cell.x(), cell.y());
  }
  return sum / (kMaxCellScore * static_cast<double>(points.size()));
}

Eigen::Matrix3d SurfaceCovariance(const SearchProblem& problem, const Candidate& best,
                                  double resolution, double angular_step,
                                  const SurfaceOptions& options) {
  const int headings = problem.scans->headings();
  const double points = static_cast<double>(std::max<std::size_t>(problem.scans->points(), 1));
  const double k = std::min(points, options.effective_points) / (kMaxCellScore * points);
  double total = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int dh = -options.radius_headings; dh <= options.radius_headings; ++dh) {
    int h = best.heading + dh;
    if (problem.headings_wrap) h = (h % headings + headings) % headings;
    if (h < 0 || h >= headings) continue;
    const int stride = std::max(1, options.stride_cells);
    const int radius = options.radius_cells / stride * stride;
    for (int dx = -radius; dx <= radius; dx += stride) {
      for (int dy = -radius; dy <= radius; dy += stride) {
        const int score = ScoreCandidate(problem, 0, h, best.x + dx, best.y + dy);
        const double weight = std::exp(k * (score - best.score));
        const Eigen::Vector3d d(dx * resolution, dy * resolution, dh * angular_step);
        total += weight;
        first += weight * d;
        second += weight * d * d.transpose();
      }
    }
  }
  const Eigen::Vector3d mean = first / total;
  Eigen::Matrix3d covariance = second / total - mean * mean.transpose();
  const Eigen::Vector3d quantization(resolution, resolution, angular_step);
  covariance.diagonal() += quantization.cwiseProduct(quantization) / 12.0;
  return covariance;
}

}  // namespace flat2d::localization
