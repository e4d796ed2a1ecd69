#include "localization/matching/rotated_scans.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace flat2d::localization {
namespace {

std::int32_t FloorCell(double v) {
  constexpr double kLimit = 1.0e9;  // far beyond any map: just "outside"
  return static_cast<std::int32_t>(std::floor(std::clamp(v, -kLimit, kLimit)));
}

}  // namespace

HeadingSet ChooseHeadings(double resolution, double max_range, double half_angle,
                          double fixed_step, int max_headings) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double step = fixed_step;
  if (!(step > 0.0)) {
    const double range = std::max(max_range, resolution);
    step = std::acos(1.0 - resolution * resolution / (2.0 * range * range));
  }
  max_headings = std::max(1, max_headings);
  HeadingSet set;
  int half = static_cast<int>(std::ceil(half_angle / step - 1.0e-9));
  if (2 * half + 1 >= static_cast<int>(std::ceil(kTwoPi / step))) {
    set.count = std::min(static_cast<int>(std::ceil(kTwoPi / step)), max_headings);
    set.step = kTwoPi / set.count;
    set.center = set.count / 2;
    return set;
  }
  if (2 * half + 1 > max_headings) {
    half = (max_headings - 1) / 2;
    step = half > 0 ? half_angle / half : 0.0;
  }
  set.count = 2 * half + 1;
  set.step = step;
  set.center = half;
  return set;
}

RotatedScans::RotatedScans(int max_headings, std::size_t max_points)
    : max_points_(max_points),
      max_headings_(max_headings),
      offsets_(static_cast<std::size_t>(max_headings) * max_points) {}

void RotatedScans::Prepare(std::span<const Eigen::Vector2d> points, const Se2& prediction,
                           const HeadingSet& headings, const GridGeometry& geometry) {
  headings_ = std::min(headings.count, max_headings_);
  points_ = std::min(points.size(), max_points_);
  const Eigen::Vector2d start = (prediction.translation() - geometry.origin) / geometry.resolution;
  for (int h = 0; h < headings_; ++h) {
    const double theta = prediction.theta() + headings.Offset(h);
    const Eigen::Matrix2d rotation =
        Eigen::Rotation2Dd(theta).toRotationMatrix() / geometry.resolution;
    CellOffset* out = offsets_.data() + static_cast<std::size_t>(h) * max_points_;
    for (std::size_t i = 0; i < points_; ++i) {
      const Eigen::Vector2d cell = rotation * points[i] + start;
      out[i] = {FloorCell(cell.x()), FloorCell(cell.y())};
    }
  }
}

}  // namespace flat2d::localization
