#include "localization/tools/grid_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "hal/net/datagram_source.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::localization {
namespace {

using hal::velodyne::Fan;
using hal::velodyne::Revolution;

// Consumes the gridder's published grids: keeps the wanted one or accumulates them all.
class GridCollector {
 public:
  GridCollector(const GridRunOptions& options, GridRunResult& result) : options_(options), result_(result) {
    if (options.accumulate) {
      const double margin = options.grid.size_m() / 2.0;
      accumulator_.emplace(CoveringGeometry(options.poses, options.grid.resolution_m(), margin),
                           options.accumulation);
    }
  }

  void Take(const maps::PublishedGrid* published) {
    if (published == nullptr) return;
    if (accumulator_) result_.fans_without_pose += static_cast<std::uint64_t>(published->fans_without_pose);
    if (!published->complete) {
      if (!accumulator_ && !partial_grid_ && published->fans > 0) {
        partial_ = *published;
        partial_grid_ = *published->grid;  // the published grid is reused by the next turn
      }
      return;
    }
    const std::uint64_t index = result_.grids_complete++;
    if (options_.on_grid) options_.on_grid(*published);
    if (accumulator_) {
      // A revolution outside the poses' time span has no frame to vote in.
      if (published->fans_without_pose > 0) return;
      accumulator_->Add(*published->grid, published->local_T_grid);
      ++result_.grids_accumulated;
    } else if (index == static_cast<std::uint64_t>(options_.revolution)) {
      Keep(*published, *published->grid);
    }
  }

  void Finish() {
    if (accumulator_ && result_.grids_accumulated > 0) result_.grid = accumulator_->Result();
    // Without a complete revolution, the first partial one stands in for revolution 0.
    if (!accumulator_ && result_.grids_complete == 0 && options_.revolution == 0 && partial_grid_) {
      Keep(partial_, std::move(*partial_grid_));
    }
  }

 private:
  void Keep(const maps::PublishedGrid& published, maps::ClassGrid grid) {
    result_.grid = std::move(grid);
    result_.grid_complete = published.complete;
    result_.fans_without_pose = static_cast<std::uint64_t>(published.fans_without_pose);
    result_.frame_T_grid = published.local_T_grid;
    result_.grid_start_ns = published.start_ns;
    result_.grid_end_ns = published.end_ns;
  }

  const GridRunOptions& options_;
  GridRunResult& result_;
  std::optional<maps::GridAccumulator> accumulator_;
  maps::PublishedGrid partial_;                // the first partial revolution's metadata...
  std::optional<maps::ClassGrid> partial_grid_;  // ...and its grid
};

}  // namespace

maps::GridGeometry CoveringGeometry(const std::vector<maps::StampedPose2d>& poses,
                                    double resolution_m, double margin_m) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const maps::StampedPose2d& pose : poses) {
    low = low.cwiseMin(pose.position);
    high = high.cwiseMax(pose.position);
  }
  if (poses.empty()) low = high = Eigen::Vector2d::Zero();
  low -= Eigen::Vector2d::Constant(margin_m);
  high += Eigen::Vector2d::Constant(margin_m);
  maps::GridGeometry geometry;
  geometry.resolution_m = resolution_m;
  // Cell edges on multiples of the resolution, so grids of one frame share cell borders.
  geometry.origin = (low / resolution_m).array().floor() * resolution_m;
  geometry.width = static_cast<int>(std::ceil((high.x() - geometry.origin.x()) / resolution_m));
  geometry.height = static_cast<int>(std::ceil((high.y() - geometry.origin.y()) / resolution_m));
  return geometry;
}

Result<GridRunResult> RunGrid(const GridRunOptions& options) {
  if (options.accumulate && options.poses.empty()) {
    return Error{"accumulating revolutions needs poses (--poses, or --can with --dbc and --odometry)"};
  }
  if (Status valid = maps::ValidateStructureGridOptions(options.grid); !valid.ok()) return valid.error();
  auto source = hal::net::OpenCapture(options.capture);
  if (!source.ok()) return source.error();

  GridRunResult result;
  GridCollector collector(options, result);
  std::optional<maps::InterpolatedPoses> poses;
  if (!options.poses.empty()) poses.emplace(options.poses);
  std::optional<maps::RevolutionGridder> gridder;
  std::optional<Error> failure;
  hal::velodyne::VelodyneStream* stream = nullptr;

  // The laser table is known once the stream has identified the model, which it has by its
  // first revolution; the gridder is created then.
  auto on_revolution = [&](const Revolution& revolution) {
    if (failure) return;
    if (!gridder) {
      const hal::velodyne::LaserTable table =
          options.stream.calibration ? *options.stream.calibration
                                     : hal::velodyne::DefaultLaserTable(stream->identification()->model);
      auto created = maps::RevolutionGridder::Create(table, options.grid, poses ? &*poses : nullptr,
                                                     options.stream.revolution.cut_azimuth_rad);
      if (!created.ok()) {
        failure = created.error();
        return;
      }
      gridder.emplace(std::move(*created));
    }
    collector.Take(gridder->Add(revolution.fans));
  };
  hal::velodyne::VelodyneStream velodyne(options.stream, on_revolution);
  stream = &velodyne;
  while (auto datagram = (*source)->Next()) velodyne.Push(*datagram);
  velodyne.Finish();
  if (gridder) collector.Take(gridder->Flush());
  collector.Finish();

  result.stream = velodyne.stats();
  result.identification = velodyne.identification();
  if (failure) return *failure;
  if (velodyne.model_error()) result.unsupported = velodyne.model_error()->message;
  return result;
}

Result<std::optional<maps::ClassGrid>> GridCaptureAtPoses(const std::filesystem::path& capture,
                                                          const maps::StructureGridOptions& grid,
                                                          const hal::velodyne::VelodyneStreamOptions& stream,
                                                          const maps::AccumulationOptions& accumulation,
                                                          const std::vector<hal::trajectory::StampedPose>& trajectory) {
  GridRunOptions pass;
  pass.capture = capture;
  pass.grid = grid;
  pass.stream = stream;
  for (const hal::trajectory::StampedPose& p : trajectory) pass.poses.push_back(maps::Flatten(p.time_ns, p.world_T_body));
  pass.accumulate = true;
  pass.accumulation = accumulation;
  auto mosaic = RunGrid(pass);
  if (!mosaic.ok()) return mosaic.error();
  return std::move(mosaic->grid);
}

}  // namespace flat2d::localization
