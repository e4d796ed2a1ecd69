#include "localization/tools/drive_map_build.hpp"

#include <cmath>

#include "hal/common/time.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "localization/tools/odometry_poses.hpp"

namespace flat2d::localization {
namespace {

std::vector<Eigen::Vector2d> SlammableCells(const maps::ClassGrid& grid) {
  std::vector<Eigen::Vector2d> points;
  const maps::GridGeometry& g = grid.geometry();
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (grid.at({col, row}) == maps::CellClass::kSlammable) points.push_back(g.CellCenter({col, row}));
    }
  }
  return points;
}

// The first keyframe starts at the anchor's pose, but one pose fixes the map's heading only
// as well as the first few matches do: a tenth of a degree off moves the far end of a
// 300 m drive by half a metre. The anchor is a track (GNSS, or the simulator's truth), so
// the optimized map is moved by the rigid motion that best fits all its keyframes to it.
void FitToAnchor(const std::vector<evaluation::TimedPose>& anchor, mapping::MapBuilder& builder) {
  std::vector<evaluation::TimedPose> keyframes;
  for (const mapping::Keyframe& k : builder.keyframes()) keyframes.push_back({k.time_s, k.estimate});
  // The anchor sampled at the keyframes' times (it is the denser of the two).
  const evaluation::TrajectoryError fit = evaluation::EvaluateTrajectory(anchor, keyframes, true);
  if (fit.poses >= 2) builder.TransformEstimate(fit.reference_T_estimate.Inverse());
}

// The scale of the similarity that best maps the keyframes' positions onto the track's at the
// same times (Umeyama 1991, in the plane). Noise in the track averages out over the drive's
// extent: its standard error is the fixes' noise / (extent x sqrt(fixes)), 2e-5 for a survey
// receiver around the campus lap and 9e-4 for 1 m fixes, against the 0.1-0.2 % the builder's
// own estimate is off (docs/benchmarks.md).
struct ScaleFit {
  double scale = 1.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // the keyframes' centroid
  int pairs = 0;
};

ScaleFit FitScale(const std::vector<evaluation::TimedPose>& track, const mapping::MapBuilder& builder) {
  // The keyframes (every half metre) are read at each fix's time, not the fixes at the
  // keyframes': a line between fixes a second apart cuts the corners of every curve, and
  // the track would look smaller than the drive by a fraction of a per cent.
  constexpr double kMaxGapS = 2.0;  // between keyframes: longer is a stop without keyframes
  std::vector<evaluation::TimedPose> keyframes;
  for (const mapping::Keyframe& k : builder.keyframes()) keyframes.push_back({k.time_s, k.estimate});
  std::vector<Eigen::Vector2d> from, to;
  for (const evaluation::TimedPose& fix : track) {
    Se2 keyframe;
    if (!evaluation::PoseAt(keyframes, fix.time_s, kMaxGapS, keyframe)) continue;
    from.push_back(keyframe.translation());
    to.push_back(fix.pose.translation());
  }
  ScaleFit fit;
  fit.pairs = static_cast<int>(from.size());
  if (fit.pairs < 3) return fit;
  Eigen::Vector2d to_centre = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    fit.centre += from[i];
    to_centre += to[i];
  }
  fit.centre /= fit.pairs;
  to_centre /= fit.pairs;
  double dot = 0.0, cross = 0.0, spread = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d a = from[i] - fit.centre, b = to[i] - to_centre;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
    spread += a.squaredNorm();
  }
  // The best rotation's cosine and sine are dot and cross over their norm; the scale is the
  // rotated correlation over the keyframes' spread.
  if (spread > 0.0) fit.scale = std::hypot(dot, cross) / spread;
  return fit;
}

}  // namespace

Result<DriveBuildResult> BuildFromDrive(const DriveBuildOptions& options) {
  auto odometry = DeadReckonedPoses(options.dbc, options.odometry_config, options.can_log);
  if (!odometry.ok()) return odometry.error();
  if (odometry->size() < 2) return MakeError(options.can_log.string() + ": fewer than 2 odometry poses");

  DriveBuildResult result;
  mapping::MapBuilder builder(options.builder);
  GridRunOptions pass;
  pass.capture = options.capture;
  pass.grid = options.grid;
  pass.stream = options.stream;
  pass.poses = *odometry;
  pass.on_grid = [&](const maps::PublishedGrid& published) {
    ++result.revolutions;
    if (published.fans_without_pose > 0) return;  // outside the CAN log's time
    const double time_s = static_cast<double>(published.start_ns) * kSecondsPerNs;
    if (builder.keyframes().empty() && !options.anchor.empty()) {
      Se2 anchor;
      if (!evaluation::PoseAt(options.anchor, time_s, 1.0, anchor)) return;  // before the anchor's time
      builder.SetAnchor(anchor);
    }
    builder.AddScan(time_s, Se2Of(published.local_T_grid), SlammableCells(*published.grid));
  };
  auto first = RunGrid(pass);
  if (!first.ok()) return first.error();
  if (first->unsupported) return MakeError(options.capture.string() + ": " + *first->unsupported);
  builder.Finish();
  result.stats = builder.stats();
  if (builder.keyframes().empty()) return result;  // nothing to map: no mosaic
  if (!options.scale_track.empty()) {
    const ScaleFit fit = FitScale(options.scale_track, builder);
    if (fit.pairs < 3) return MakeError("fewer than 3 fixes of the scale track fall within the keyframes' time");
    builder.ScaleEstimate(fit.scale, fit.centre);
    result.track_scale = fit.scale;
    result.track_scale_fixes = fit.pairs;
  }
  if (!options.anchor.empty()) FitToAnchor(options.anchor, builder);

  std::vector<maps::StampedPose2d> corrected;
  for (const maps::StampedPose2d& p : *odometry) {
    const double time_s = static_cast<double>(p.time_ns) * kSecondsPerNs;
    const Se2 odom(p.position, p.yaw);
    const Se2 world = builder.CorrectedPose(time_s, odom);
    result.odometry.push_back({time_s, odom});
    result.estimate.push_back({time_s, world});
    corrected.push_back({p.time_ns, world.translation(), world.theta()});
  }
  GridRunOptions second;
  second.capture = options.capture;
  second.grid = options.grid;
  second.stream = options.stream;
  second.poses = std::move(corrected);
  second.accumulate = true;
  second.accumulation = options.accumulation;
  auto mosaic = RunGrid(second);
  if (!mosaic.ok()) return mosaic.error();
  result.mosaic = std::move(mosaic->grid);
  result.keyframes = builder.keyframes();
  result.stats = builder.stats();
  return result;
}

}  // namespace flat2d::localization
