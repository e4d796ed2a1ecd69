#include "localization/tools/prior_map_output.hpp"

#include <cmath>

#include "maps/grid/grid_crop.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/prior_map/viewpoint.hpp"
#include "maps/render/class_grid_image.hpp"
#include "maps/render/png_writer.hpp"

namespace flat2d::localization::tools {
namespace {

// A viewpoint sub-map every `spacing` metres along the path.
std::vector<maps::ViewpointGrid> MakeViewpoints(const maps::ClassGrid& mosaic, const std::vector<mapping::Keyframe>& path,
                                                double spacing, double range) {
  std::vector<maps::ViewpointGrid> viewpoints;
  if (spacing <= 0.0) return viewpoints;
  double next = 0.0;
  for (const mapping::Keyframe& k : path) {
    if (k.path_m < next) continue;
    next = k.path_m + spacing;
    viewpoints.push_back({k.estimate.x(), k.estimate.y(), k.estimate.theta(), k.time_s,
                          maps::VisibleFrom(mosaic, k.estimate.translation(), range)});
  }
  return viewpoints;
}

Status WritePreview(const maps::ClassGrid& mosaic, const std::vector<evaluation::TimedPose>& trajectory,
                    const std::vector<maps::ViewpointGrid>& viewpoints, const std::filesystem::path& path) {
  maps::RgbImage image = maps::RenderClassGrid(mosaic);
  const maps::GridGeometry& g = mosaic.geometry();
  auto plot = [&](const Eigen::Vector2d& p, maps::Rgb colour, int radius) {
    const int col = static_cast<int>(std::floor((p.x() - g.origin.x()) / g.resolution_m));
    const int row = g.height - 1 - static_cast<int>(std::floor((p.y() - g.origin.y()) / g.resolution_m));
    for (int dr = -radius; dr <= radius; ++dr)
      for (int dc = -radius; dc <= radius; ++dc) image.SetClipped(col + dc, row + dr, colour);
  };
  for (const evaluation::TimedPose& p : trajectory) plot(p.pose.translation(), {30, 90, 230}, 0);
  for (const maps::ViewpointGrid& v : viewpoints) plot({v.x_m, v.y_m}, {20, 170, 40}, 2);
  return maps::WritePng(image, path);
}

}  // namespace

Result<MapOutput> WriteBuiltMap(maps::ClassGrid mosaic, const std::vector<mapping::Keyframe>& path,
                                const std::vector<evaluation::TimedPose>& trajectory,
                                const std::filesystem::path& out, const MapOutputOptions& options) {
  if (auto cropped = maps::CropToObserved(mosaic, 4)) mosaic = std::move(*cropped);
  const auto viewpoints = MakeViewpoints(mosaic, path, options.viewpoint_spacing_m, options.viewpoint_range_m);
  if (Status s = maps::WritePriorMap(mosaic, out, options.write, viewpoints); !s.ok()) return s.error();
  if (options.png) {
    if (Status s = WritePreview(mosaic, trajectory, viewpoints, *options.png); !s.ok()) return s.error();
  }
  return MapOutput{viewpoints.size()};
}

std::vector<mapping::Keyframe> PathOf(const std::vector<hal::trajectory::StampedPose>& trajectory,
                                      std::vector<evaluation::TimedPose>& planar) {
  std::vector<mapping::Keyframe> path;
  double path_m = 0.0;
  for (const hal::trajectory::StampedPose& p : trajectory) {
    const maps::StampedPose2d flat = maps::Flatten(p.time_ns, p.world_T_body);
    const Se2 pose(flat.position, flat.yaw);
    if (!path.empty()) path_m += (pose.translation() - path.back().estimate.translation()).norm();
    mapping::Keyframe k;
    k.time_s = static_cast<double>(p.time_ns) * 1e-9;
    k.estimate = pose;
    k.path_m = path_m;
    path.push_back(std::move(k));
    planar.push_back({k.time_s, pose});
  }
  return path;
}

Result<MapOutput> WriteTrajectoryMap(maps::ClassGrid mosaic, const std::vector<hal::trajectory::StampedPose>& trajectory,
                                     const std::filesystem::path& out, const std::string& created_by,
                                     const std::string& source) {
  std::vector<evaluation::TimedPose> planar;
  const std::vector<mapping::Keyframe> path = PathOf(trajectory, planar);
  MapOutputOptions output;
  output.write.created_by = created_by;
  output.write.source = source;
  output.png = out / "map.png";
  return WriteBuiltMap(std::move(mosaic), path, planar, out / "map.f2m", output);
}

}  // namespace flat2d::localization::tools
