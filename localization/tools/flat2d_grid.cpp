// flat2d-grid: structure grids from a Velodyne capture (thesis 7.1). One revolution's grid,
// or, given poses, every revolution accumulated into one grid in the poses' frame.
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read, is invalid or cannot
// be written, 3 no grid (no decodable data, or not that many revolutions).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "hal/common/angles.hpp"
#include "hal/velodyne/calibration_yaml.hpp"
#include "localization/tools/grid_run.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/class_grid_file.hpp"
#include "maps/grid/grid_crop.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/render/class_grid_image.hpp"
#include "maps/render/png_writer.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-grid";

constexpr const char* kUsage = R"(usage:
  flat2d-grid [options] CAPTURE --out STEM      one revolution's grid, or all of them with poses

output (at least one):
  --out STEM            class grid in the map_server convention: STEM.pgm + STEM.yaml
                        (slammable 0, hazard 128, free 254, unknown 205)
  --png FILE            the grid in the thesis' colours (black slammable, red hazard,
                        white free, grey unknown)
  --json                a summary as one JSON object on stdout
  --no-crop             keep the whole grid (default: cropped to the observed cells)

poses (motion compensation, and the frame of an accumulated grid):
  --poses FILE.tum      vehicle poses (truth or estimate, TUM "t x y z qx qy qz qw");
                        every revolution is accumulated into one grid in their frame
  --can LOG --dbc DBC --odometry CONFIG
                        dead-reckon a candump log instead (the odometry frame)
  --accumulate          accumulate with CAN poses too (always on with --poses)
  --revolution N        without accumulation: which complete revolution (default 0)
  --min-votes N         accumulation: observations needed for structure (default 2)
  --min-fraction F      ... and the share of them that saw it (default 0.3)

method and thresholds (override the configuration):
  --config FILE         StructureGridOptions text file (default: the shipped
                        packaging/config/grid/structure_grid.textproto)
  --method slope|cartesian|polar
  --hazard-deg D        slope method: hazard above D degrees (thesis 15)
  --slammable-deg D     slope method: slammable above D degrees (thesis 80)
  --fit-points N        slope over N returns (2 = consecutive)
  --hazard-popcount N, --slammable-popcount N   popcount methods: bands for each class
  --fill-in on|off      hole fill-in between fans (thesis 7.1.4)
  --fill-in-gap M       its distance bound (thesis 0.25)
  --resolution M        cell size (default 0.05)
  --size M              side of the per-revolution grid (default 50)
  --free-range M        ray-cast free space up to M metres
  --mounting-z M        sensor height above the ground

capture:
  --model NAME          VLP-16 | HDL-32E | VLP-32C (default: identified from the packets)
  --calibration FILE    calibration YAML
  --cut-angle DEG       azimuth where revolutions are cut (default 0)
)";

struct Options {
  localization::GridRunOptions run;
  std::string config;
  std::optional<std::string> out, png, poses, can, dbc, odometry, calibration;
  bool json = false;
  bool accumulate = false;
  bool crop = true;
  maps::StructureGridOptions overrides;  // applied over the configuration
  std::vector<std::string> set_fields;   // which overrides were given
};

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

maps::StructureGridOptions::Method ParseMethod(std::string_view name) {
  if (name == "slope") return maps::StructureGridOptions::METHOD_SLOPE;
  if (name == "cartesian") return maps::StructureGridOptions::METHOD_CARTESIAN_POPCOUNT;
  if (name == "polar") return maps::StructureGridOptions::METHOD_POLAR_POPCOUNT;
  Fail(1, "--method takes slope, cartesian or polar, not " + std::string(name));
}

bool ParseOnOff(std::string_view flag, std::string_view text) {
  if (text == "on") return true;
  if (text == "off") return false;
  Fail(1, std::string(flag) + " takes on or off, not " + std::string(text));
}

// Applies one method/threshold option to `grid`; false if `arg` is not one.
bool ApplyGridOption(std::string_view arg, const char* text, maps::StructureGridOptions& grid) {
  auto number = [&] { return maps::cli::ParseNumber(kTool, arg, text); };
  auto integer = [&] { return static_cast<int>(maps::cli::ParseInteger(kTool, arg, text, 1, 64)); };
  if (arg == "--method") grid.set_method(ParseMethod(text));
  else if (arg == "--hazard-deg") grid.mutable_slope()->set_hazard_slope_deg(number());
  else if (arg == "--slammable-deg") grid.mutable_slope()->set_slammable_slope_deg(number());
  else if (arg == "--fit-points") grid.mutable_slope()->set_fit_points(integer());
  else if (arg == "--hazard-popcount") grid.mutable_popcount()->set_hazard_popcount(integer());
  else if (arg == "--slammable-popcount") grid.mutable_popcount()->set_slammable_popcount(integer());
  else if (arg == "--fill-in") grid.mutable_fill_in()->set_enabled(ParseOnOff(arg, text));
  else if (arg == "--fill-in-gap") grid.mutable_fill_in()->set_max_gap_m(number());
  else if (arg == "--resolution") grid.set_resolution_m(number());
  else if (arg == "--size") grid.set_size_m(number());
  else if (arg == "--free-range") grid.set_free_space_range_m(number());
  else if (arg == "--mounting-z") grid.mutable_mounting()->set_z_m(number());
  else return false;
  return true;
}

Options ParseOptions(int argc, char** argv) {
  Options options;
  options.config = localization::ShippedGridConfig();
  std::vector<std::pair<std::string, const char*>> grid_options;  // applied after --config
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    auto& run = options.run;
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--json") options.json = true;
    else if (arg == "--no-crop") options.crop = false;
    else if (arg == "--out") options.out = value();
    else if (arg == "--png") options.png = value();
    else if (arg == "--poses") options.poses = value();
    else if (arg == "--can") options.can = value();
    else if (arg == "--dbc") options.dbc = value();
    else if (arg == "--odometry") options.odometry = value();
    else if (arg == "--accumulate") options.accumulate = true;
    else if (arg == "--config") options.config = value();
    else if (arg == "--calibration") options.calibration = value();
    else if (arg == "--revolution") {
      run.revolution = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 10'000'000));
    } else if (arg == "--min-votes") {
      run.accumulation.min_structure_votes = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 65535));
    } else if (arg == "--min-fraction") {
      run.accumulation.min_structure_fraction = maps::cli::ParseNumber(kTool, arg, value());
      if (!(run.accumulation.min_structure_fraction > 0.0 && run.accumulation.min_structure_fraction <= 1.0)) {
        Fail(1, "--min-fraction must be in (0, 1]");
      }
    } else if (arg == "--model") {
      const char* name = value();
      run.stream.model = hal::velodyne::ParseModelName(name);
      if (!run.stream.model) Fail(1, std::string("unknown model: ") + name);
    } else if (arg == "--cut-angle") {
      run.stream.revolution.cut_azimuth_rad = maps::cli::ParseNumber(kTool, arg, value()) * kDegToRad;
    } else if (arg.starts_with("--")) {
      maps::StructureGridOptions probe;
      const char* text = value();
      if (!ApplyGridOption(arg, text, probe)) Fail(1, "unknown option " + std::string(arg) + "\n" + kUsage);
      grid_options.emplace_back(std::string(arg), text);
    } else if (run.capture.empty()) {
      run.capture = std::string(arg);
    } else {
      Fail(1, "more than one capture given");
    }
  }
  if (options.run.capture.empty()) Fail(1, std::string("no capture given\n") + kUsage);
  if (!options.out && !options.png && !options.json) Fail(1, "nothing to write: give --out, --png or --json");
  if (options.poses && options.can) Fail(1, "give --poses or --can, not both");
  if (options.can && (!options.dbc || !options.odometry)) Fail(1, "--can needs --dbc and --odometry");
  if (options.accumulate && !options.poses && !options.can) Fail(1, "--accumulate needs --poses or --can");

  auto loaded = maps::LoadStructureGridOptions(options.config);
  if (!loaded.ok()) Fail(2, loaded.error().message);
  options.run.grid = *loaded;
  for (const auto& [flag, text] : grid_options) ApplyGridOption(flag, text, options.run.grid);
  if (Status valid = maps::ValidateStructureGridOptions(options.run.grid); !valid.ok()) {
    Fail(1, valid.error().message);
  }
  return options;
}

void LoadInputs(Options& options) {
  if (options.calibration) {
    auto table = hal::velodyne::LoadCalibrationYaml(*options.calibration, options.run.stream.model);
    if (!table.ok()) Fail(2, table.error().message);
    options.run.stream.calibration = *table;
  }
  if (options.poses) {
    auto poses = localization::TumPoses(*options.poses);
    if (!poses.ok()) Fail(2, poses.error().message);
    options.run.poses = std::move(*poses);
    options.run.accumulate = true;
  } else if (options.can) {
    auto poses = localization::DeadReckonedPoses(*options.dbc, *options.odometry, *options.can);
    if (!poses.ok()) Fail(2, poses.error().message);
    options.run.poses = std::move(*poses);
    options.run.accumulate = options.accumulate;
  }
}

std::string MethodName(maps::StructureGridOptions::Method method) {
  switch (method) {
    case maps::StructureGridOptions::METHOD_CARTESIAN_POPCOUNT: return "cartesian";
    case maps::StructureGridOptions::METHOD_POLAR_POPCOUNT: return "polar";
    default: return "slope";
  }
}

std::string SummaryJson(const Options& options, const localization::GridRunResult& result) {
  const maps::ClassGrid& grid = *result.grid;
  const maps::GridGeometry& g = grid.geometry();
  const Eigen::Isometry2d& pose = result.frame_T_grid;
  const double yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  std::ostringstream out;
  out.precision(12);
  out << "{\"capture\":\"" << options.run.capture.string() << "\"";
  if (result.identification) {
    out << ",\"product\":\"" << hal::velodyne::ModelName(result.identification->model) << "\""
        << ",\"return_mode\":\"" << hal::velodyne::ReturnModeName(result.identification->return_mode) << "\"";
  }
  out << ",\"method\":\"" << MethodName(options.run.grid.method()) << "\""
      << ",\"fill_in\":" << (options.run.grid.fill_in().enabled() ? "true" : "false")
      << ",\"accumulated\":" << (options.run.accumulate ? "true" : "false")
      << ",\"revolutions\":" << result.grids_complete
      << ",\"revolutions_accumulated\":" << result.grids_accumulated
      << ",\"fans_without_pose\":" << result.fans_without_pose
      << ",\"data_packets\":" << result.stream.data_packets
      << ",\"malformed\":" << result.stream.malformed
      << ",\"width\":" << g.width << ",\"height\":" << g.height
      << ",\"resolution_m\":" << g.resolution_m
      << ",\"origin\":[" << g.origin.x() << "," << g.origin.y() << "]"
      << ",\"cells\":{\"unknown\":" << grid.Count(maps::CellClass::kUnknown)
      << ",\"free\":" << grid.Count(maps::CellClass::kFree)
      << ",\"hazard\":" << grid.Count(maps::CellClass::kHazard)
      << ",\"slammable\":" << grid.Count(maps::CellClass::kSlammable) << "}";
  if (!options.run.accumulate) {
    out << ",\"revolution\":" << options.run.revolution
        << ",\"complete\":" << (result.grid_complete ? "true" : "false")
        << ",\"start_time\":" << static_cast<double>(result.grid_start_ns) * 1e-9
        << ",\"end_time\":" << static_cast<double>(result.grid_end_ns) * 1e-9
        << ",\"reference_pose\":{\"x\":" << pose.translation().x() << ",\"y\":" << pose.translation().y()
        << ",\"yaw\":" << yaw << "}";
  }
  out << "}";
  return out.str();
}

void WriteOutputs(const Options& options, const maps::ClassGrid& grid) {
  if (options.out) {
    if (Status written = maps::WriteClassGrid(grid, *options.out); !written.ok()) Fail(2, written.error().message);
  }
  if (options.png) {
    if (Status written = maps::WritePng(maps::RenderClassGrid(grid), *options.png); !written.ok()) {
      Fail(2, written.error().message);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options = ParseOptions(argc, argv);
  LoadInputs(options);
  auto result = localization::RunGrid(options.run);
  if (!result.ok()) Fail(2, result.error().message);
  if (result->unsupported) Fail(3, *result->unsupported);
  if (!result->grid) {
    Fail(3, options.run.accumulate
                ? "no complete revolution within the poses' time span"
                : "the capture has " + std::to_string(result->grids_complete) +
                      " complete revolutions; --revolution " + std::to_string(options.run.revolution) +
                      " is not among them");
  }
  if (options.crop) {
    // One cell of margin, so the observed region's edge stays inside the picture.
    if (auto cropped = maps::CropToObserved(*result->grid, 1)) result->grid = std::move(*cropped);
  }
  WriteOutputs(options, *result->grid);
  if (options.json) std::cout << SummaryJson(options, *result) << "\n";
  return 0;
}
