#include "localization/tools/features_command.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

#include "hal/sim/worlds.hpp"
#include "localization/tools/features_report.hpp"
#include "localization/tools/features_run.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kFeaturesUsage = R"(
features: 3D lines and planes of LiDAR revolutions (thesis 8.1): the spherical image,
non-vertical region removal (Algorithm 7), normals, region growing (Algorithm 8) and line /
plane fitting (Eq. 8.4-8.6). INPUT: a Velodyne capture (.pcap, .pcapng), a .pcd sweep or a
KITTI .bin. One revolution (a cloud file, or --revolution N) prints every plane (normal, d,
points, residual) and line (point, direction, points, residual) and the stage times; a whole
capture prints the summary per revolution.
  --revolution N        only the N-th complete revolution of a capture (from 0)
  --features-config F   extraction options (default packaging/config/features3d/features3d.textproto)
  --config F            structure-grid options: the sensor's mounting, for gravity (default the
                        shipped structure_grid.textproto); cloud files take z as up
  --world W --truth T   judge against a simulator run: the world (flat2d-sim --world) and its
                        truth.tum; the revolutions are deskewed by the truth; adds precision,
                        recall and parameter errors within 20 m (docs/benchmarks.md)
  --drive N             the run's drive (flat2d-sim --drive; default 0): where traffic is
  --no-vertical-removal every point goes on to normals and segmentation (Fig. 8.7)
  --join both|either    Algorithm 8's rule (both, default) or the text's (either)
  --json                one JSON object
  --png OUT             a top-down picture of the (last) revolution: clusters, planes, lines
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";

struct FeaturesArgs {
  std::optional<std::string> input, features_config, grid_config, world, truth, png;
  int revolution = -1;
  int drive = 0;
  bool vertical_removal = true;
  std::optional<maps::features3d::SegmentationOptions::JoinRule> join;
  bool json = false;
};

FeaturesArgs ParseArgs(int argc, char** argv) {
  FeaturesArgs a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return std::string(maps::cli::OptionValue(kTool, argc, argv, i)); };
    if (arg == "--revolution") a.revolution = static_cast<int>(maps::cli::ParseInteger(kTool, arg, maps::cli::OptionValue(kTool, argc, argv, i), 0, 1'000'000));
    else if (arg == "--features-config") a.features_config = value();
    else if (arg == "--config") a.grid_config = value();
    else if (arg == "--world") a.world = value();
    else if (arg == "--truth") a.truth = value();
    else if (arg == "--drive") a.drive = static_cast<int>(maps::cli::ParseInteger(kTool, arg, maps::cli::OptionValue(kTool, argc, argv, i), 0, 100));
    else if (arg == "--no-vertical-removal") a.vertical_removal = false;
    else if (arg == "--join") {
      const std::string rule = value();
      if (rule != "both" && rule != "either") maps::cli::Fail(kTool, 1, "features: --join is both or either");
      a.join = rule == "both" ? maps::features3d::SegmentationOptions::BOTH : maps::features3d::SegmentationOptions::EITHER;
    } else if (arg == "--json") a.json = true;
    else if (arg == "--png") a.png = value();
    else if (arg == "--help" || arg == "-h") {
      std::printf("usage: flat2d-map features INPUT [options]\n%s", kFeaturesUsage);
      std::exit(0);
    } else if (!arg.empty() && arg.front() == '-') maps::cli::Fail(kTool, 1, "features: unknown argument " + std::string(arg));
    else if (!a.input) a.input = std::string(arg);
    else maps::cli::Fail(kTool, 1, "features: one INPUT only");
  }
  if (!a.input) maps::cli::Fail(kTool, 1, std::string("features needs an INPUT\n") + kFeaturesUsage);
  if (a.world.has_value() != a.truth.has_value()) maps::cli::Fail(kTool, 1, "features: --world and --truth go together");
  return a;
}

// The run's options from the arguments and the configuration files; Fail(2) on a bad file.
FeaturesRunOptions RunOptions(const FeaturesArgs& a) {
  FeaturesRunOptions options;
  options.input = *a.input;
  options.revolution = a.revolution;
  auto extraction = maps::features3d::LoadFeatureOptions(a.features_config.value_or(ShippedFeaturesConfig()));
  if (!extraction.ok()) maps::cli::Fail(kTool, 2, extraction.error().message);
  options.extraction = *extraction;
  options.extraction.mutable_vertical()->set_enabled(options.extraction.vertical().enabled() && a.vertical_removal);
  if (a.join) options.extraction.mutable_segmentation()->set_join(*a.join);
  auto grid = maps::LoadStructureGridOptions(a.grid_config.value_or(ShippedGridConfig()));
  if (!grid.ok()) maps::cli::Fail(kTool, 2, grid.error().message);
  options.vehicle_T_sensor = maps::VehicleFromSensor(grid->mounting());
  if (!a.world) return options;
  auto world = hal::sim::BuiltInWorld(*a.world);
  if (!world.ok()) maps::cli::Fail(kTool, 2, world.error().message);
  if (a.drive >= world->drives_size()) maps::cli::Fail(kTool, 1, "features: the world has no drive " + std::to_string(a.drive));
  options.world = *world;
  options.world_time_offset_s = world->drives(a.drive).world_time_offset_s();
  auto truth = hal::trajectory::ReadTum(*a.truth);
  if (!truth.ok()) maps::cli::Fail(kTool, 2, truth.error().message);
  options.truth = std::move(*truth);
  return options;
}

}  // namespace

int FeaturesCommand(int argc, char** argv) {
  const FeaturesArgs a = ParseArgs(argc, argv);
  const FeaturesRunOptions options = RunOptions(a);
  FeaturesSummary summary;
  std::string single;  // one revolution's full report
  std::optional<Error> picture_error;
  const Status run = RunFeatures(options, [&](const RevolutionFeatures& r) {
    summary.Add(r);
    single = a.json ? FeaturesJson(r) : FeaturesText(r);
    if (a.png) {
      const Status written = WriteFeaturesPng(r, *a.png);
      if (!written.ok()) picture_error = written.error();
    }
  });
  if (!run.ok()) maps::cli::Fail(kTool, 2, run.error().message);
  if (picture_error) maps::cli::Fail(kTool, 2, picture_error->message);
  const std::string out = summary.revolutions() == 1 && !options.world ? single : (a.json ? summary.Json() : summary.Text());
  std::fputs(out.c_str(), stdout);
  return 0;
}

}  // namespace flat2d::localization::tools
