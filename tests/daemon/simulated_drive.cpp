#include "tests/daemon/simulated_drive.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

#include "hal/sim/simulation.hpp"
#include "hal/sim/simulation_sinks.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/localizer/localizer_config.hpp"
#include "localization/odometry/odometry_config.hpp"
#include "localization/tools/drive_map_build.hpp"
#include "maps/grid/grid_crop.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/prior_map/prior_map_file.hpp"

namespace flat2d::daemon::testing {
namespace {

const std::filesystem::path kSource(FLAT2D_SOURCE_DIR);

void Simulate(int drive, std::uint64_t seed, const std::filesystem::path& dir) {
  hal::sim::SimulationOptions options;
  options.world = std::string("occluders");
  options.drive = drive;
  options.seed = seed;
  options.lidar = hal::sim::DefaultLidarOptions(hal::velodyne::Model::kVlp16);
  hal::sim::FileSinkOptions files;
  files.truth_map = false;
  auto sink = hal::sim::FileSink::Open(dir, files);
  ASSERT_TRUE(sink.ok()) << sink.error().message;
  hal::sim::SimulationSink* sinks[] = {&*sink};
  auto summary = hal::sim::RunSimulation(options, sinks);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
}

maps::StructureGridOptions ShippedGrid() {
  auto grid = maps::LoadStructureGridOptions(kSource / "packaging/config/grid/structure_grid.textproto");
  EXPECT_TRUE(grid.ok());
  return *grid;
}

void BuildMap(const std::filesystem::path& mapping, const std::filesystem::path& out) {
  localization::DriveBuildOptions options;
  options.capture = mapping / hal::sim::kLidarFile;
  options.can_log = mapping / hal::sim::kCanFile;
  options.dbc = mapping / hal::sim::kDbcFile;
  options.odometry_config = kSource / "packaging/config/odometry/flat2d_sim.textproto";
  options.grid = ShippedGrid();
  options.builder.point_range_m = std::min(options.builder.point_range_m, options.grid.size_m() / 2.0);
  options.builder.odometry = {0.01, 0.01, 0.01, 0.001, 0.0, 0};  // flat2d-map build's for drives
  auto anchor = localization::evaluation::ReadTrajectory(mapping / hal::sim::kTruthFile);
  ASSERT_TRUE(anchor.ok());
  options.anchor = std::move(*anchor);
  auto built = localization::BuildFromDrive(options);
  ASSERT_TRUE(built.ok()) << built.error().message;
  ASSERT_TRUE(built->mosaic.has_value());
  maps::ClassGrid mosaic = std::move(*built->mosaic);
  if (auto cropped = maps::CropToObserved(mosaic, 4)) mosaic = std::move(*cropped);
  ASSERT_TRUE(maps::WritePriorMap(mosaic, out, maps::PriorMapWriteOptions{}, {}).ok());
}

SimulatedDrive Make() {
  SimulatedDrive drive;
  drive.dir = std::filesystem::temp_directory_path() / ("flat2d_daemon_drive_" + std::to_string(::getpid()));
  std::filesystem::create_directories(drive.dir);
  Simulate(0, 5, drive.dir / "mapping");
  Simulate(2, 6, drive.dir / "drive2");
  drive.map = drive.dir / "occluders.f2m";
  BuildMap(drive.dir / "mapping", drive.map);
  drive.capture = drive.dir / "drive2" / hal::sim::kLidarFile;
  drive.can_log = drive.dir / "drive2" / hal::sim::kCanFile;
  drive.dbc = drive.dir / "drive2" / hal::sim::kDbcFile;
  auto truth = localization::evaluation::ReadTrajectory(drive.dir / "drive2" / hal::sim::kTruthFile);
  EXPECT_TRUE(truth.ok());
  if (truth.ok()) drive.truth = std::move(*truth);
  static const std::filesystem::path scratch = drive.dir;
  std::atexit([] { std::filesystem::remove_all(scratch); });
  return drive;
}

}  // namespace

const SimulatedDrive& OccludersDrive() {
  static const SimulatedDrive drive = Make();
  return drive;
}

std::unique_ptr<localization::LocalizationPipeline> MakeShippedPipeline(const SimulatedDrive& drive) {
  auto dbc = hal::can::LoadDbc(drive.dbc);
  auto odometry = localization::LoadOdometryConfig(kSource / "packaging/config/odometry/flat2d_sim.textproto");
  auto localizer = localization::LoadLocalizerOptions(kSource / "packaging/config/localizer/localizer.textproto");
  EXPECT_TRUE(dbc.ok() && odometry.ok() && localizer.ok());
  auto map = maps::PriorMapReader::Open(drive.map, localizer->map_cache_tiles);
  EXPECT_TRUE(map.ok());
  localization::LocalizationPipelineOptions options;
  options.grid = ShippedGrid();
  options.localizer = *localizer;
  auto pipeline = localization::LocalizationPipeline::Create(*dbc, *odometry, std::move(*map), options);
  EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
  return std::move(*pipeline);
}

}  // namespace flat2d::daemon::testing
