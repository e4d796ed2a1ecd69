#include "tests/daemon/simulated_drive.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <optional>

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

constexpr char kCompleteMarker[] = "complete";

// The files of a drive made in `dir`.
SimulatedDrive At(const std::filesystem::path& dir) {
  SimulatedDrive drive;
  drive.dir = dir;
  drive.map = dir / "occluders.f2m";
  drive.capture = dir / "drive2" / hal::sim::kLidarFile;
  drive.can_log = dir / "drive2" / hal::sim::kCanFile;
  drive.dbc = dir / "drive2" / hal::sim::kDbcFile;
  auto truth = localization::evaluation::ReadTrajectory(dir / "drive2" / hal::sim::kTruthFile);
  EXPECT_TRUE(truth.ok()) << truth.error().message;
  if (truth.ok()) drive.truth = std::move(*truth);
  return drive;
}

// Simulates both drives and builds the map in `dir`; `complete` is written last, so a
// folder without it (an interrupted run) is never read as a drive.
void MakeIn(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Simulate(0, 5, dir / "mapping");
  Simulate(2, 6, dir / "drive2");
  if (::testing::Test::HasFatalFailure()) return;
  BuildMap(dir / "mapping", dir / "occluders.f2m");
  if (::testing::Test::HasFatalFailure()) return;
  std::ofstream(dir / kCompleteMarker) << "made by tests/daemon/simulated_drive.cpp\n";
}

std::optional<std::filesystem::path> SharedDir() {
  const char* shared = std::getenv("FLAT2D_SHARED_DRIVE");
  if (shared == nullptr || *shared == '\0') return std::nullopt;
  return std::filesystem::path(shared);
}

SimulatedDrive Make() {
  if (const auto shared = SharedDir()) {
    if (!std::filesystem::exists(*shared / kCompleteMarker)) MakeIn(*shared);
    return At(*shared);
  }
  static const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("flat2d_daemon_drive_" + std::to_string(::getpid()));
  MakeIn(scratch);
  std::atexit([] { std::filesystem::remove_all(scratch); });
  return At(scratch);
}

}  // namespace

const SimulatedDrive& OccludersDrive() {
  static const SimulatedDrive drive = Make();
  return drive;
}

bool RemakeSharedDrive() {
  const auto shared = SharedDir();
  if (!shared) return false;
  MakeIn(*shared);
  return true;
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
