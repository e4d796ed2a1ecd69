// flat2d-map: prior maps (issue 8). build: a drive or a 2D laser log through the map builder
// into a prior map file (grid_build_command.hpp), or a 3D build by --mode (nicp, landmarks,
// catacomb); info: what a map file holds; render: a map (or a region of it) as a picture or
// a map_server class grid; register, features, calibrate: the 3D tools (issues 11-13).
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read, is invalid or cannot
// be written, 3 nothing to map (no keyframe).
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "localization/tools/catacomb_command.hpp"
#include "localization/tools/grid_build_command.hpp"
#include "localization/tools/nicp_build_command.hpp"
#include "localization/tools/nicp_drive_command.hpp"
#include "localization/tools/calibrate_command.hpp"
#include "localization/tools/export_command.hpp"
#include "localization/tools/features_command.hpp"
#include "localization/tools/landmark_drive_command.hpp"
#include "localization/tools/register_command.hpp"
#include "maps/grid/class_grid_file.hpp"
#include "maps/prior_map/prior_map_reader.hpp"
#include "maps/prior_map/prior_map_region.hpp"
#include "maps/prior_map/prior_map_summary.hpp"
#include "maps/render/class_grid_image.hpp"
#include "maps/render/png_writer.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-map";

constexpr const char* kUsage = R"(usage:
  flat2d-map build --carmen LOG --out MAP [options]
  flat2d-map build --pcap CAPTURE --can LOG --dbc DBC --odometry CONFIG --out MAP [options]
  flat2d-map info MAP [--json]
  flat2d-map render MAP --out FILE [--region XMIN,YMIN,XMAX,YMAX]
  flat2d-map build --mode nicp LIST --out DIR [options]
  flat2d-map build --mode nicp DRIVE.pcap --out DIR [--can LOG --dbc DBC --odometry CONFIG] [options]
  flat2d-map register SOURCE TARGET [--init FILE] [--method M] [--json] [options]
  flat2d-map features INPUT [--revolution N] [--json] [--png OUT] [options]
  flat2d-map calibrate DRIVE [DRIVE2] [--json] [options]
  flat2d-map build --mode landmarks DRIVE.pcap --out DIR --can LOG --dbc DBC --odometry CONFIG [options]
  flat2d-map build --mode catacomb DRIVE.pcap --out DIR [--can LOG --dbc DBC --odometry CONFIG] [options]
  flat2d-map export DRIVE --out DIR --can LOG --dbc DBC --odometry CONFIG [--truth T.tum] [options]

info: tiles, mapped area, file bytes, resolution, georeference (--json: one JSON object).
render: FILE ending in .png is a picture in the thesis' colours; otherwise FILE (without
.yaml/.pgm) is the stem of a map_server class grid (as flat2d-grid --out writes), which
flat2d-eval grid compares with a truth map. --region clips to a box in the map frame.
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

// The value of --mode: grid (the default), nicp, landmarks or catacomb.
std::string_view BuildMode(int argc, char** argv) {
  for (int i = 0; i + 1 < argc; ++i) {
    if (std::string_view(argv[i]) != "--mode") continue;
    const std::string_view mode = argv[i + 1];
    if (mode != "nicp" && mode != "grid" && mode != "landmarks" && mode != "catacomb") {
      Fail(1, "build: --mode is grid (default), nicp, landmarks or catacomb");
    }
    return mode;
  }
  return "grid";
}

int Build(int argc, char** argv) {
  const std::string_view mode = BuildMode(argc, argv);
  if (mode == "landmarks") return localization::tools::LandmarkDriveCommand(argc, argv);
  if (mode == "catacomb") return localization::tools::CatacombCommand(argc, argv);
  if (mode == "nicp") {
    return localization::tools::IsDriveBuild(argc, argv) ? localization::tools::NicpDriveCommand(argc, argv)
                                                         : localization::tools::NicpBuildCommand(argc, argv);
  }
  return localization::tools::GridBuildCommand(argc, argv);
}


int Info(int argc, char** argv) {
  std::optional<std::string> path;
  bool json = false;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--json") json = true;
    else if (!arg.starts_with("-") && !path) path = argv[i];
    else Fail(1, "info: unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (!path) Fail(1, std::string("info needs a MAP\n") + kUsage);
  auto reader = maps::PriorMapReader::Open(*path, 1);
  if (!reader.ok()) Fail(2, reader.error().message);
  const maps::PriorMapSummary summary = maps::SummarizePriorMap(*reader);
  std::printf("%s", json ? (maps::SummaryJson(summary) + "\n").c_str()
                         : maps::SummaryText(summary).c_str());
  return 0;
}

int Render(int argc, char** argv) {
  std::optional<std::string> path, out, region_text;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    if (arg == "--out") out = value();
    else if (arg == "--region") region_text = value();
    else if (!arg.starts_with("-") && !path) path = argv[i];
    else Fail(1, "render: unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (!path || !out) Fail(1, std::string("render needs MAP and --out FILE\n") + kUsage);
  auto reader = maps::PriorMapReader::Open(*path, 16);
  if (!reader.ok()) Fail(2, reader.error().message);
  std::optional<maps::MapRegion> region = maps::StoredExtent(*reader);
  if (region_text) {
    const auto v = maps::cli::ParseNumberList(kTool, "--region", *region_text, 4);
    region = maps::MapRegion{{v[0], v[1]}, {v[2], v[3]}};
  }
  if (!region) Fail(3, *path + ": the map stores no tile");
  auto grid = maps::ReadRegion(*reader, *region);
  if (!grid.ok()) Fail(2, grid.error().message);
  std::string target = *out;
  Status written = Status::Ok();
  if (target.ends_with(".png")) {
    written = maps::WritePng(maps::RenderClassGrid(*grid), target);
  } else {
    if (target.ends_with(".yaml") || target.ends_with(".pgm")) target.resize(target.size() - (target.ends_with(".pgm") ? 4 : 5));
    written = maps::WriteClassGrid(*grid, target);
  }
  if (!written.ok()) Fail(2, written.error().message);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string_view command = argc >= 2 ? argv[1] : "";
  if (command == "build") return Build(argc - 2, argv + 2);
  if (command == "info") return Info(argc - 2, argv + 2);
  if (command == "render") return Render(argc - 2, argv + 2);
  if (command == "register") return localization::tools::RegisterCommand(argc - 2, argv + 2);
  if (command == "features") return localization::tools::FeaturesCommand(argc - 2, argv + 2);
  if (command == "calibrate") return localization::tools::CalibrateCommand(argc - 2, argv + 2);
  if (command == "export") return localization::tools::ExportCommand(argc - 2, argv + 2);
  if (command == "--help" || command == "-h") {
    std::cout << kUsage << localization::tools::kGridBuildUsage << localization::tools::kNicpBuildUsage << localization::tools::kNicpDriveUsage
              << localization::tools::kRegisterUsage << localization::tools::kFeaturesUsage
              << localization::tools::kLandmarkDriveUsage << localization::tools::kCalibrateUsage
              << localization::tools::kCatacombUsage << localization::tools::kExportUsage;
    return 0;
  }
  Fail(1, std::string("unknown or missing command\n") + kUsage);
}
