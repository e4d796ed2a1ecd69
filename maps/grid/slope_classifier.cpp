#include "maps/grid/slope_classifier.hpp"

#include <algorithm>
#include <cassert>
#include <array>
#include <cmath>

namespace flat2d::maps {

namespace {

// The most returns one fan holds (a 64-laser sensor).
constexpr std::size_t kMaxFanReturns = 64;

// The longest fit window: a few returns; more would smooth away the obstacles themselves.
constexpr int kMaxFitPoints = 8;

Eigen::Vector2d ProfilePoint(const Eigen::Vector3f& point) {
  return {std::hypot(static_cast<double>(point.x()), static_cast<double>(point.y())),
          static_cast<double>(point.z())};
}

CellClass ClassOfSlope(double slope, const SlopeThresholds& thresholds) {
  if (slope > thresholds.slammable_slope_rad) return CellClass::kSlammable;
  if (slope > thresholds.hazard_slope_rad) return CellClass::kHazard;
  return CellClass::kFree;
}

// Step (5): pairs (i, j > i + 1) of returns whose returns in between all lie farther away
// than both. Scanning j upwards, once a return between is no farther than return i, no
// later pair with i qualifies.
void MarkSeeThroughPairs(std::span<const Eigen::Vector2d> points, const SlopeThresholds& thresholds,
                         std::span<CellClass> classes) {
  const double steep = std::tan(thresholds.slammable_slope_rad);
  for (std::size_t i = 0; i + 2 < points.size(); ++i) {
    const Eigen::Vector2d& a = points[i];
    if (a.y() > thresholds.see_through_max_height_m) continue;
    double nearest_between = points[i + 1].x();
    for (std::size_t j = i + 2; j < points.size() && nearest_between > a.x(); ++j) {
      const Eigen::Vector2d& b = points[j];
      if (b.y() <= thresholds.see_through_max_height_m && nearest_between > b.x() &&
          std::abs(b.y() - a.y()) > steep * std::abs(b.x() - a.x())) {
        const std::size_t nearer = a.x() <= b.x() ? i : j;
        classes[nearer] = Strongest(classes[nearer], CellClass::kSlammable);
      }
      nearest_between = std::min(nearest_between, b.x());
    }
  }
}

}  // namespace

double ProfileSlope(std::span<const Eigen::Vector2d> profile) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : profile) mean += p;
  mean /= static_cast<double>(profile.size());
  double sxx = 0.0, sxz = 0.0, szz = 0.0;
  for (const Eigen::Vector2d& p : profile) {
    const Eigen::Vector2d d = p - mean;
    sxx += d.x() * d.x();
    sxz += d.x() * d.y();
    szz += d.y() * d.y();
  }
  // Principal axis angle of the 2x2 scatter matrix: 0.5 atan2(2 sxz, sxx - szz).
  const double angle = 0.5 * std::atan2(2.0 * sxz, sxx - szz);
  return std::abs(angle);
}

void ClassifyFan(std::span<const Eigen::Vector3f> returns, const SlopeThresholds& thresholds,
                 std::span<CellClass> classes) {
  std::fill(classes.begin(), classes.end(), CellClass::kUnknown);
  assert(returns.size() <= kMaxFanReturns);
  const std::size_t count = std::min(returns.size(), kMaxFanReturns);
  const std::size_t window = static_cast<std::size_t>(std::clamp(thresholds.fit_points, 2, kMaxFitPoints));
  // The profile once per fan: index 0 is the dummy return, index k > 0 is returns[k - 1].
  std::array<Eigen::Vector2d, kMaxFanReturns + 1> points;
  points[0] = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < count; ++k) points[k + 1] = ProfilePoint(returns[k]);
  auto profile_at = [&](std::size_t k) { return points[k]; };
  std::array<Eigen::Vector2d, kMaxFitPoints> profile;
  for (std::size_t first = 0; first + window <= count + 1; ++first) {
    std::size_t nearest = first;  // profile index of the window's return nearest the vehicle
    for (std::size_t k = 0; k < window; ++k) {
      profile[k] = profile_at(first + k);
      if (profile[k].x() < profile[nearest - first].x()) nearest = first + k;
    }
    const CellClass window_class = ClassOfSlope(ProfileSlope({profile.data(), window}), thresholds);
    if (window_class == CellClass::kFree) {
      for (std::size_t k = std::max<std::size_t>(first, 1); k < first + window; ++k) {
        classes[k - 1] = Strongest(classes[k - 1], CellClass::kFree);
      }
    } else if (nearest != 0) {  // the dummy return is the vehicle's own place
      classes[nearest - 1] = Strongest(classes[nearest - 1], window_class);
    }
  }
  if (thresholds.see_through_max_height_m > 0.0) {
    MarkSeeThroughPairs(std::span(points).subspan(1, count), thresholds, classes);
  }
}

}  // namespace flat2d::maps
