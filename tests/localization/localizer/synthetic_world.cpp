#include "tests/localization/localizer/synthetic_world.hpp"

#include <cmath>
#include <numbers>

#include "maps/prior_map/prior_map_file.hpp"

namespace flat2d::testing {
namespace {

using localization::Se2;

constexpr double kSpeed = 5.0;             // m/s
constexpr double kHalfLength = 18.0;       // the path's straight parts: 2 x 36 m and 2 x 16 m
constexpr double kHalfWidth = 8.0;
constexpr double kCornerRadius = 5.0;
constexpr double kSpeedScale = 1.01;       // odometry reads 1 % long
constexpr double kYawRateBias = 0.005;     // rad/s
constexpr double kScanRange = 20.0;        // structure seen up to here

maps::ClassGrid Yard() {
  maps::GridGeometry g;
  g.resolution_m = 0.05;
  g.width = 1300;
  g.height = 1100;
  g.origin = Eigen::Vector2d(-32.5, -27.5);
  maps::ClassGrid grid(g);
  auto wall = [&](double x0, double y0, double x1, double y1) {
    grid.MarkLine({x0, y0}, {x1, y1}, maps::CellClass::kSlammable);
  };
  wall(-30, -25, 30, -25);  // the yard
  wall(30, -25, 30, 25);
  wall(30, 25, -30, 25);
  wall(-30, 25, -30, -25);
  wall(-10, -3, 6, -3);  // inner walls of different lengths and angles
  wall(-4, 3, 12, 4);
  wall(-22, -14, -22, 6);
  wall(22, -16, 25, -10);
  wall(-14, 14, -6, 20);
  wall(8, -20, 14, -21);
  for (int i = 0; i < 14; ++i) {  // pillars 0.3 m square, irregularly spaced
    const double x = -26.0 + 3.7 * i + 0.6 * std::sin(1.7 * i);
    const double y = (i % 2 == 0 ? 13.0 : -13.5) + 0.8 * std::cos(2.3 * i);
    for (double dx = -0.15; dx <= 0.15; dx += 0.05) {
      wall(x + dx, y - 0.15, x + dx, y + 0.15);
    }
  }
  return grid;
}

// Arc length along the rounded rectangle to a pose (x, y, heading), anticlockwise from the
// middle of its south side.
Se2 PathPose(double s) {
  const double straight_x = 2.0 * (kHalfLength - kCornerRadius);
  const double straight_y = 2.0 * (kHalfWidth - kCornerRadius);
  const double quarter = std::numbers::pi / 2.0 * kCornerRadius;
  const double lap = 2.0 * (straight_x + straight_y) + 4.0 * quarter;
  s = std::fmod(s + straight_x / 2.0, lap);
  const double sides[4] = {straight_x, straight_y, straight_x, straight_y};
  // Corners' centres, anticlockwise from south-east.
  const Eigen::Vector2d centres[4] = {{kHalfLength - kCornerRadius, -kHalfWidth + kCornerRadius},
                                      {kHalfLength - kCornerRadius, kHalfWidth - kCornerRadius},
                                      {-kHalfLength + kCornerRadius, kHalfWidth - kCornerRadius},
                                      {-kHalfLength + kCornerRadius, -kHalfWidth + kCornerRadius}};
  const Eigen::Vector2d starts[4] = {{-kHalfLength + kCornerRadius, -kHalfWidth},
                                     {kHalfLength, -kHalfWidth + kCornerRadius},
                                     {kHalfLength - kCornerRadius, kHalfWidth},
                                     {-kHalfLength, kHalfWidth - kCornerRadius}};
  for (int side = 0; side < 4; ++side) {
    const double heading = side * std::numbers::pi / 2.0;
    if (s < sides[side]) {
      return Se2(starts[side] + s * Eigen::Vector2d(std::cos(heading), std::sin(heading)), heading);
    }
    s -= sides[side];
    if (s < quarter) {
      const double a = heading - std::numbers::pi / 2.0 + s / kCornerRadius;
      return Se2(centres[side] + kCornerRadius * Eigen::Vector2d(std::cos(a), std::sin(a)),
                 heading + s / kCornerRadius);
    }
    s -= quarter;
  }
  return Se2(starts[0], 0.0);
}

}  // namespace

SyntheticWorld::SyntheticWorld(const std::filesystem::path& map_path, double duration_s) {
  const maps::ClassGrid yard = Yard();
  const maps::GridGeometry& g = yard.geometry();
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (yard.at({col, row}) == maps::CellClass::kSlammable) structure_.push_back(g.CellCenter({col, row}));
    }
  }
  // Exact arcs of the scaled speed and the biased yaw rate: the truth's steps, lengthened
  // and turned a little more each; the covariance of a MEMS-grade dead reckoning.
  const double dt = static_cast<double>(kOdometryNs) * 1e-9;
  const Eigen::Matrix3d step_covariance = Eigen::Vector3d(4e-5, 4e-5, 1e-6).asDiagonal() * dt;
  localization::OdometrySample sample;
  Se2 previous = TruthAt(0);
  const auto samples = static_cast<std::size_t>(duration_s / dt) + 1;
  for (std::size_t i = 0; i < samples; ++i) {
    sample.time_ns = static_cast<TimeNs>(i) * kOdometryNs;
    if (i > 0) {
      const Se2 truth = TruthAt(sample.time_ns);
      const Se2 step = previous.Inverse() * truth;
      const Se2 measured = localization::Arc(kSpeedScale * step.translation().norm(), step.theta() + kYawRateBias * dt);
      sample.covariance = localization::ComposeCovariance(sample.local_T_vehicle, sample.covariance, measured, step_covariance);
      sample.local_T_vehicle = sample.local_T_vehicle * measured;
      sample.step_covariance = step_covariance;
      previous = truth;
    }
    odometry_.push_back(sample);
  }
  maps::PriorMapWriteOptions options;
  options.created_utc = "2026-01-01T00:00:00Z";
  (void)maps::WritePriorMap(yard, map_path, options);
}

Se2 SyntheticWorld::TruthAt(TimeNs t) const { return PathPose(kSpeed * static_cast<double>(t) * 1e-9); }

const localization::OdometrySample& SyntheticWorld::OdometryAt(TimeNs t) const {
  return odometry_.at(static_cast<std::size_t>(t / kOdometryNs));
}

maps::ClassGrid SyntheticWorld::MakeScanGrid() {
  maps::GridGeometry g;
  g.resolution_m = 0.05;
  g.width = g.height = static_cast<int>(2.0 * kScanRange / g.resolution_m);
  g.origin = Eigen::Vector2d(-kScanRange, -kScanRange);
  return maps::ClassGrid(g);
}

maps::PublishedGrid SyntheticWorld::Revolution(int k, maps::ClassGrid& grid, bool empty) const {
  const TimeNs start = k * kRevolutionNs;
  grid.Clear();
  if (!empty) {
    const Se2 vehicle_T_map = TruthAt(start).Inverse();
    for (const Eigen::Vector2d& p : structure_) {
      const Eigen::Vector2d local = vehicle_T_map * p;
      if (local.squaredNorm() < kScanRange * kScanRange) grid.Mark(local, maps::CellClass::kSlammable);
    }
  }
  const Se2 odometry = OdometryAt(start).local_T_vehicle;
  maps::PublishedGrid published;
  published.grid = &grid;
  published.local_T_grid = Eigen::Isometry2d::Identity();
  published.local_T_grid.translate(odometry.translation());
  published.local_T_grid.rotate(odometry.theta());
  published.start_ns = start;
  published.end_ns = start + kRevolutionNs - kNsPerMs;
  published.sequence = static_cast<std::uint64_t>(k);
  published.complete = true;
  published.fans = 1800;
  return published;
}

}  // namespace flat2d::testing
