#include "localization/mapping/carmen_map_build.hpp"

#include <cmath>
#include <limits>

namespace flat2d::localization::mapping {
namespace {

Se2 PoseOf(const hal::carmen::CarmenPose& pose) { return Se2(pose.x, pose.y, pose.theta); }

// The world grid, aligned to the resolution, holding every scan end at its pose.
maps::GridGeometry MosaicGeometry(const std::vector<std::vector<Eigen::Vector2d>>& points,
                                  const std::vector<evaluation::TimedPose>& poses, double resolution_m) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = -low;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    low = low.cwiseMin(poses[i].pose.translation());
    high = high.cwiseMax(poses[i].pose.translation());
    for (const Eigen::Vector2d& p : points[i]) {
      const Eigen::Vector2d q = poses[i].pose * p;
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
  }
  maps::GridGeometry g;
  g.resolution_m = resolution_m;
  g.origin = ((low.array() / resolution_m).floor() - 2.0) * resolution_m;
  g.width = static_cast<int>(std::ceil((high.x() - g.origin.x()) / resolution_m)) + 2;
  g.height = static_cast<int>(std::ceil((high.y() - g.origin.y()) / resolution_m)) + 2;
  return g;
}

// One scan as a class grid in the world frame, aligned with `world`: free along each beam,
// slammable at its end.
maps::ClassGrid RasterizeScan(const std::vector<Eigen::Vector2d>& points, const Se2& pose,
                              const maps::GridGeometry& world) {
  Eigen::Vector2d low = pose.translation(), high = pose.translation();
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d q = pose * p;
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const double r = world.resolution_m;
  maps::GridGeometry g;
  g.resolution_m = r;
  g.origin = world.origin + r * ((low - world.origin).array() / r).floor().matrix() - Eigen::Vector2d::Constant(r);
  g.width = static_cast<int>(std::ceil((high.x() - g.origin.x()) / r)) + 2;
  g.height = static_cast<int>(std::ceil((high.y() - g.origin.y()) / r)) + 2;
  maps::ClassGrid grid(g);
  for (const Eigen::Vector2d& p : points) grid.MarkLine(pose.translation(), pose * p, maps::CellClass::kFree);
  for (const Eigen::Vector2d& p : points) grid.Mark(pose * p, maps::CellClass::kSlammable);
  return grid;
}

}  // namespace

MapBuilderOptions LaserLogBuilderOptions() {
  MapBuilderOptions options;
  options.local_map_keyframes = 10;
  options.map_min_votes = 1;
  options.refine_sweeps = 0;
  options.estimate_odometry_scale = false;
  options.fuse_tracking = false;  // a laser log's odometry is the noise model's: the match is better
  options.match_sigma_floor_m = 0.02;
  options.match_sigma_floor_rad = 0.005;
  return options;
}

std::vector<Eigen::Vector2d> ScanPointsOf(const hal::carmen::LaserScan& scan, double min_range_m, double max_range_m) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double range = static_cast<double>(scan.ranges[i]);
    if (!std::isfinite(range) || range < min_range_m || range > max_range_m) continue;
    if (scan.max_range > 0.0 && range >= scan.max_range) continue;
    const double bearing = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    points.emplace_back(range * std::cos(bearing), range * std::sin(bearing));
  }
  return points;
}

Result<CarmenBuildResult> BuildFromCarmen(const std::vector<hal::carmen::LaserScan>& scans,
                                          const CarmenBuildOptions& options) {
  if (scans.size() < 2) return MakeError("map build: the log holds fewer than 2 laser scans");
  CarmenBuildResult result;
  std::vector<Se2> reference;
  for (const auto& scan : scans) reference.push_back(PoseOf(scan.laser_pose));
  const std::vector<Se2> odometry = CorruptOdometry(reference, options.noise);

  // Trajectories need increasing times; some logs repeat or step back (csail's are printed
  // with 6 significant digits, intel steps back 4 times): such a scan is put 1 ms after the
  // previous one.
  std::vector<double> times(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    times[i] = scans[i].timestamp;
    if (i > 0 && !(times[i] > times[i - 1])) {
      times[i] = times[i - 1] + 1e-3;
      ++result.times_adjusted;
    }
  }

  MapBuilder builder(options.builder);
  std::vector<std::vector<Eigen::Vector2d>> points;
  points.reserve(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    points.push_back(ScanPointsOf(scans[i], options.min_range_m, options.max_range_m));
    if (i == 0) builder.SetAnchor(reference.front());
    builder.AddScan(times[i], odometry[i], points.back());
    result.reference.push_back({times[i], reference[i]});
    result.odometry.push_back({times[i], odometry[i]});
  }
  builder.Finish();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    result.estimate.push_back({times[i], builder.CorrectedPose(times[i], odometry[i])});
  }

  maps::GridAccumulator accumulator(MosaicGeometry(points, result.estimate, options.mosaic_resolution_m),
                                    options.accumulation);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    accumulator.Add(RasterizeScan(points[i], result.estimate[i].pose, accumulator.geometry()),
                    Eigen::Isometry2d::Identity());
  }
  result.mosaic = accumulator.Result();
  result.stats = builder.stats();
  result.keyframes = builder.keyframes();
  return result;
}

}  // namespace flat2d::localization::mapping
