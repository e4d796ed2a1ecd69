#include "maps/features3d/feature_fit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

namespace flat2d::maps::features3d {
namespace {

struct ClusterShape {
  Eigen::Vector3d mean;
  Eigen::Vector3d eigenvalues;  // ascending
  Eigen::Matrix3d axes;         // columns u1, u2, u3
  int count = 0;
};

ClusterShape ShapeOf(const std::vector<Eigen::Vector3f>& points, std::span<const std::int32_t> indices) {
  ClusterShape shape;
  shape.count = static_cast<int>(indices.size());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const std::int32_t i : indices) sum += points[static_cast<std::size_t>(i)].cast<double>();
  shape.mean = sum / static_cast<double>(indices.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // about the mean: no cancellation far away
  for (const std::int32_t i : indices) {
    const Eigen::Vector3d e = points[static_cast<std::size_t>(i)].cast<double>() - shape.mean;
    covariance.noalias() += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance / static_cast<double>(indices.size()));
  shape.eigenvalues = solver.eigenvalues().cwiseMax(0.0);
  shape.axes = solver.eigenvectors();
  return shape;
}

// Half the spread of the points along `axis` about the mean, and their mean distance from
// the model (Eq. 8.4): `distance(e)` of each point's offset e from the mean.
template <typename Distance>
std::pair<double, double> ExtentAndResidual(const std::vector<Eigen::Vector3f>& points, std::span<const std::int32_t> indices,
                                            const Eigen::Vector3d& mean, const Eigen::Vector3d& axis, Distance distance) {
  double low = 0.0, high = 0.0, residual = 0.0;
  for (const std::int32_t i : indices) {
    const Eigen::Vector3d e = points[static_cast<std::size_t>(i)].cast<double>() - mean;
    const double along = e.dot(axis);
    low = std::min(low, along);
    high = std::max(high, along);
    residual += distance(e);
  }
  return {0.5 * (high - low), residual / static_cast<double>(indices.size())};
}

// The sensor sees the near half of a pole, sampled about evenly across it (y = r sin(theta)
// uniform in [-r, r]): the points' spread across it is l2 = r^2 / 3.
double CrossSectionRadius(const ClusterShape& shape) { return std::sqrt(3.0 * shape.eigenvalues(1)); }

// From the mean of a pole's points to its axis: their depths sqrt(r^2 - y^2) average
// (pi / 4) r in front of the axis, along u1 (the depth direction of a round cross-section).
Eigen::Vector3d AxisOffset(const ClusterShape& shape) {
  const double radius = CrossSectionRadius(shape);
  Eigen::Vector3d away = shape.axes.col(0);
  if (away.dot(shape.mean) < 0.0) away = -away;  // the sensor is at the origin
  return (std::numbers::pi / 4.0 * radius) * away;
}

double FloorVariance(double variance) { return std::max(variance, kMinResidualSigmaM * kMinResidualSigmaM); }

std::optional<LineFeature> FitLine(const ClusterShape& shape, const std::vector<Eigen::Vector3f>& points,
                                   std::span<const std::int32_t> indices, const FittingOptions& options) {
  const Eigen::Vector3d& l = shape.eigenvalues;
  if (!((l(0) + l(1)) < options.line_max_spread() * l.sum())) return std::nullopt;  // Eq. 8.5, shape
  if (l(0) < options.line_min_roundness() * l(1)) return std::nullopt;              // a flat strip
  LineFeature line;
  line.point = shape.mean;
  line.direction = shape.axes.col(2) * (shape.axes(2, 2) < 0.0 ? -1.0 : 1.0);
  line.across = shape.axes.col(0);
  const auto [half_length, residual] = ExtentAndResidual(points, indices, shape.mean, line.direction, [&](const Eigen::Vector3d& e) {
    return (e - e.dot(line.direction) * line.direction).norm();
  });
  if (!(residual < options.line_max_residual_m())) return std::nullopt;  // Eq. 8.5, residual
  const double min_radius = options.line_axis_min_radius_m();
  if (min_radius > 0.0 && CrossSectionRadius(shape) >= min_radius) line.point += AxisOffset(shape);
  line.half_length_m = half_length;
  line.residual_m = residual;
  line.points = shape.count;
  const double n = shape.count;
  const double s1 = FloorVariance(l(0)), s2 = FloorVariance(l(1)), along = std::max(l(2), s2);
  line.covariance = Eigen::Vector4d(s1 / n, s2 / n, s1 / (n * along), s2 / (n * along)).asDiagonal();
  return line;
}

std::optional<PlaneFeature> FitPlane(const ClusterShape& shape, const std::vector<Eigen::Vector3f>& points,
                                     std::span<const std::int32_t> indices, const FittingOptions& options,
                                     const Eigen::Vector3f& up) {
  const Eigen::Vector3d& l = shape.eigenvalues;
  if (shape.count < static_cast<int>(options.min_plane_points())) return std::nullopt;
  if (!(l(0) < options.plane_max_flatness() * l.sum())) return std::nullopt;  // Eq. 8.6, shape
  PlaneFeature plane;
  plane.normal = shape.axes.col(1).cross(shape.axes.col(2)).normalized();
  if (plane.normal.dot(shape.mean) > 0.0) plane.normal = -plane.normal;  // towards the sensor
  plane.d = -plane.normal.dot(shape.mean);
  plane.centroid = shape.mean;
  plane.major_axis = shape.axes.col(2);
  const auto [half_major, residual] = ExtentAndResidual(points, indices, shape.mean, plane.major_axis,
                                                        [&](const Eigen::Vector3d& e) { return std::abs(e.dot(plane.normal)); });
  if (!(residual < options.plane_max_residual_m())) return std::nullopt;  // Eq. 8.6, residual
  const auto [half_minor, unused] = ExtentAndResidual(points, indices, shape.mean, shape.axes.col(1),
                                                      [](const Eigen::Vector3d&) { return 0.0; });
  if (2.0 * half_minor < options.min_plane_width_m()) return std::nullopt;  // a strip
  if (options.min_plane_height_m() > 0.0) {
    const auto [half_height, none] = ExtentAndResidual(points, indices, shape.mean, up.cast<double>(),
                                                       [](const Eigen::Vector3d&) { return 0.0; });
    if (2.0 * half_height < options.min_plane_height_m()) return std::nullopt;  // a desk, a bench
  }
  plane.half_extent = {half_major, half_minor};
  plane.residual_m = residual;
  plane.points = shape.count;
  const double n = shape.count, s = FloorVariance(l(0));
  plane.covariance = Eigen::Vector3d(s / (n * std::max(l(1), s)), s / (n * std::max(l(2), s)), s / n).asDiagonal();
  return plane;
}

}  // namespace

Feature FitFeature(const std::vector<Eigen::Vector3f>& points, std::span<const std::int32_t> indices,
                   const FittingOptions& options, const Eigen::Vector3f& up) {
  if (indices.size() < 3) return std::monostate{};
  const ClusterShape shape = ShapeOf(points, indices);
  if (auto line = FitLine(shape, points, indices, options)) return *line;
  if (auto plane = FitPlane(shape, points, indices, options, up)) return *plane;
  return std::monostate{};
}

}  // namespace flat2d::maps::features3d
