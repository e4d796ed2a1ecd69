#include "hal/sim/speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace flat2d::hal::sim {
namespace {

constexpr double kNodeSpacingM = 0.05;
constexpr double kMaxNodes = 4e6;  // bounds the tables to ~64 MB for a 200 km drive

double Reachable(double from_speed, double accel, double ds) {
  return std::sqrt(from_speed * from_speed + 2.0 * accel * ds);
}

// Each node's cap: the cruise speed, and v^2 kappa <= a_lat over the neighbouring intervals.
std::vector<double> SpeedCaps(const DrivePath& path, const SpeedLimits& limits, std::size_t nodes,
                              double ds) {
  std::vector<double> caps(nodes);
  for (std::size_t i = 0; i < nodes; ++i) {
    const double s = static_cast<double>(i) * ds;
    const double curvature = path.MaxAbsCurvature(s - ds, s + ds);
    caps[i] = limits.cruise_mps;
    if (curvature > 0.0) {
      caps[i] = std::min(caps[i], std::sqrt(limits.max_lateral_accel_mps2 / curvature));
    }
  }
  return caps;
}

// Both passes over an open path from rest to rest.
std::vector<double> OpenProfile(std::vector<double> v, double accel, double ds) {
  v.front() = 0.0;
  v.back() = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i) v[i] = std::min(v[i], Reachable(v[i - 1], accel, ds));
  for (std::size_t i = v.size() - 1; i-- > 0;) v[i] = std::min(v[i], Reachable(v[i + 1], accel, ds));
  return v;
}

// Both passes round a closed lap of caps.size() nodes; returns caps.size() + 1 speeds
// (the last is the first again).
std::vector<double> PeriodicProfile(std::vector<double> v, double accel, double ds) {
  const std::size_t n = v.size();
  const std::size_t slowest = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
  for (std::size_t step = 1; step < n; ++step) {
    const std::size_t i = (slowest + step) % n;
    v[i] = std::min(v[i], Reachable(v[(i + n - 1) % n], accel, ds));
  }
  const std::size_t slowest_after =
      static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
  for (std::size_t step = 1; step < n; ++step) {
    const std::size_t i = (slowest_after + n - step) % n;
    v[i] = std::min(v[i], Reachable(v[(i + 1) % n], accel, ds));
  }
  v.push_back(v.front());
  return v;
}

std::string Label(std::string_view drive_name) {
  return "drive '" + std::string(drive_name) + "': ";
}

}  // namespace

Result<SpeedProfile> SpeedProfile::Create(const DrivePath& path, const SpeedLimits& limits,
                                          std::string_view drive_name) {
  if (!std::isfinite(limits.cruise_mps) || limits.cruise_mps <= 0.0) {
    return MakeError(Label(drive_name) + "speed_mps must be positive");
  }
  if (!std::isfinite(limits.max_accel_mps2) || limits.max_accel_mps2 <= 0.0 ||
      !std::isfinite(limits.max_lateral_accel_mps2) || limits.max_lateral_accel_mps2 <= 0.0) {
    return MakeError(Label(drive_name) + "acceleration limits must be positive (0 = default)");
  }
  const double length = path.length();
  const double intervals = std::max(2.0, std::ceil(length / kNodeSpacingM));
  if (intervals > kMaxNodes) return MakeError(Label(drive_name) + "path too long to tabulate");

  SpeedProfile profile;
  profile.length_m_ = length;
  profile.spacing_m_ = length / intervals;
  const double ds = profile.spacing_m_;
  const double accel = limits.max_accel_mps2;
  const auto count = static_cast<std::size_t>(intervals);
  if (!path.loop()) {
    profile.first_.speed = OpenProfile(SpeedCaps(path, limits, count + 1, ds), accel, ds);
    profile.FillTimes(profile.first_);
    return profile;
  }
  profile.periodic_.speed = PeriodicProfile(SpeedCaps(path, limits, count, ds), accel, ds);
  profile.first_.speed = profile.periodic_.speed;
  for (std::size_t i = 0; i <= count; ++i) {
    profile.first_.speed[i] =
        std::min(profile.first_.speed[i], std::sqrt(2.0 * accel * static_cast<double>(i) * ds));
  }
  if (profile.first_.speed.back() < profile.periodic_.speed.back()) {
    return MakeError(Label(drive_name) + "the loop (" + std::to_string(length) +
                     " m) is too short to reach its lap speed from rest");
  }
  profile.FillTimes(profile.first_);
  profile.FillTimes(profile.periodic_);
  return profile;
}

void SpeedProfile::FillTimes(Table& table) const {
  table.time.assign(table.speed.size(), 0.0);
  for (std::size_t i = 1; i < table.speed.size(); ++i) {
    // Constant acceleration between nodes: the mean speed is the mean of the ends.
    table.time[i] = table.time[i - 1] + 2.0 * spacing_m_ / (table.speed[i - 1] + table.speed[i]);
  }
}

PathMotion SpeedProfile::Interpolate(const Table& table, double t) const {
  const auto after = std::upper_bound(table.time.begin(), table.time.end(), t);
  if (after == table.time.end()) {
    return PathMotion{length_m_, table.speed.back(), 0.0};
  }
  const std::size_t i =
      after == table.time.begin() ? 0 : static_cast<std::size_t>(after - table.time.begin()) - 1;
  const double v0 = table.speed[i];
  const double v1 = table.speed[i + 1];
  const double accel = (v1 * v1 - v0 * v0) / (2.0 * spacing_m_);
  const double tau = std::max(0.0, t - table.time[i]);
  const double start = static_cast<double>(i) * spacing_m_;
  PathMotion motion;
  motion.s = std::min(start + v0 * tau + 0.5 * accel * tau * tau, start + spacing_m_);
  motion.speed_mps = std::clamp(v0 + accel * tau, std::min(v0, v1), std::max(v0, v1));
  motion.accel_mps2 = accel;
  return motion;
}

PathMotion SpeedProfile::At(double drive_time_s) const {
  const double t = std::max(0.0, drive_time_s);
  const double first_lap = first_.duration_s();
  if (periodic_.speed.empty() || t <= first_lap) {
    PathMotion motion = Interpolate(first_, std::min(t, first_lap));
    if (periodic_.speed.empty() && t >= first_lap) motion.accel_mps2 = 0.0;
    return motion;
  }
  const double lap = periodic_.duration_s();
  const double laps_done = std::floor((t - first_lap) / lap);
  PathMotion motion = Interpolate(periodic_, t - first_lap - laps_done * lap);
  motion.s += length_m_ * (1.0 + laps_done);
  return motion;
}

}  // namespace flat2d::hal::sim
