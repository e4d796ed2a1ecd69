#include "localization/tools/grid_build_command.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/carmen/carmen_log.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/mapping/carmen_map_build.hpp"
#include "localization/tools/calibrated_odometry.hpp"
#include "localization/tools/drive_map_build.hpp"
#include "localization/tools/gnss_track.hpp"
#include "localization/tools/prior_map_output.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/prior_map/prior_map_file.hpp"
#include "maps/prior_map/prior_map_reader.hpp"
#include "maps/prior_map/prior_map_summary.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kGridBuildUsage = R"(
build: keyframes every --keyframe-distance metres or --keyframe-angle radians, each
scan-matched against the previous keyframes (tracking) and against earlier keyframes near
it (loop closures, max-mixture factors), the pose graph optimized, the mosaic of every scan
at its optimized pose written as a prior map with viewpoint sub-maps.
  --carmen LOG          a CARMEN 2D laser log (plain or .gz); its poses are the reference,
                        corrupted into odometry by the seeded noise model below
  --pcap CAPTURE --can LOG --dbc DBC --odometry CONFIG
                        a Velodyne drive: structure grids per revolution, CAN odometry
  --config FILE         drive: StructureGridOptions (default: the shipped structure_grid.textproto)
  --anchor FILE.tum     drive: a track in the map frame (GNSS, the simulator's truth.tum):
                        the first keyframe starts at its pose, the optimized map is fitted
                        to it rigidly; default: the odometry frame
  --scale-from FILE.tum drive: a GNSS track (positions; 1 Hz is enough) whose scale the
                        map takes: the similarity that best fits the keyframes to it, its
                        scale applied before the --anchor fit (the builder's own scale,
                        from odometry and matches, is 0.1-0.2 % short on long drives)
  --scale-from-gnss     drive: the same, from the GNSS fixes ($GPRMC) in the capture's
                        position packets
  --out MAP             the prior map file
  --png FILE            preview: the map, the optimized trajectory (blue), viewpoints (green)
  --trajectory FILE     the optimized trajectory (TUM): every scan, or every CAN sample
  --odometry-out FILE   the odometry the builder was given (TUM)
  --calibrated-odometry-out FILE
                        drive: the --odometry configuration with the wheel scale the build
                        measured (wheel_speed_scale x odometry_scale x track_scale), for
                        flat2d-localize and flat2dd on the same vehicle
  --reference-out FILE  carmen: the log's own poses (TUM)
  --json                a build summary as one JSON object on stdout
  --seed N              carmen: noise seed (default 1)
  --max-scans N         carmen: only the log's first N scans
  --noise-translation F --noise-lateral F --noise-rotation F --noise-rotation-per-m R
  --noise-scale F       carmen: noise model (defaults 0.05, 0.02, 0.05, 0.01 rad/m, 0.01)
  --keyframe-distance M (default 0.5) --keyframe-angle RAD (default 0.25)
  --loop-radius M       (default 4) --loop-min-path M (default 8) --loop-min-score S (0.55)
  --loop-candidates N   nearest earlier keyframes tried per keyframe (default 2)
  --local-map-keyframes N  keyframes a new one is tracked against (default 40; carmen 10)
  --refine-sweeps N     final sweeps matching each keyframe against both sides (default 2;
                        carmen 0)
  --map-min-votes N     keyframes that must see a local-map cell (default 2; carmen 1)
  --scale-estimate on|off  estimate the odometry scale (default on; carmen off)
  --odometry-scale S       the odometry's known scale (a wheel calibration): used as it
                           is with --scale-estimate off, else where too few steps pin it down
  --odometry-sigma T,R,RM
                        the odometry factors' standard deviation: T of the distance, R of
                        the turn, RM rad per metre (default: the noise model for carmen,
                        0.01,0.01,0.001 for drives)
  --match-floor-m M --match-floor-rad R
                        smallest standard deviation given a match (default 0.01, 0.002;
                        carmen 0.02, 0.005)
  --resolution M        carmen: mosaic cell size (default 0.05; drives use the grid's)
  --tile-cells N        cells a tile side (default 256)
  --viewpoint-spacing M a viewpoint sub-map every M metres of the drive (default 10; 0: none)
  --viewpoint-range M   their radius (default 20)
  --enu LAT,LON,ALT | --utm ZONE,N|S,EASTING,NORTHING
                        georeference of the map frame
)";

namespace {

using evaluation::TimedPose;

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

// The odometry factors' uncertainty for a drive's CAN odometry (wheel speeds and a gyro):
// 1 % of the distance, 1 % of the turn and 0.05 deg per metre, 1 sigma.
constexpr localization::mapping::OdometryNoiseModel kDriveOdometrySigma{0.01, 0.01, 0.01, 0.001, 0.0, 0};

struct BuildArgs {
  std::optional<std::string> carmen, pcap, can, dbc, odometry, config, anchor, scale_from;
  std::string out;
  std::optional<std::string> png, trajectory, odometry_out, reference_out, calibrated_odometry_out;
  bool json = false;
  bool scale_from_gnss = false;
  localization::mapping::MapBuilderOptions builder;
  localization::mapping::OdometryNoiseModel noise;
  std::optional<localization::mapping::OdometryNoiseModel> odometry_sigma;
  double resolution_m = 0.05;
  std::int64_t max_scans = 0;  // carmen: 0 = all
  int tile_cells = 256;
  double viewpoint_spacing_m = 10.0;
  double viewpoint_range_m = 20.0;
  maps::Georeference georeference;
};

std::vector<double> ParseList(std::string_view flag, const std::string& text, std::size_t count) {
  return maps::cli::ParseNumberList(kTool, flag, text, count);
}

maps::Georeference ParseUtm(const std::string& text) {
  // ZONE,N|S,EASTING,NORTHING
  const auto first = text.find(',');
  const auto second = first == std::string::npos ? first : text.find(',', first + 1);
  if (second == std::string::npos) Fail(1, "--utm takes ZONE,N|S,EASTING,NORTHING");
  const std::string hemisphere = text.substr(first + 1, second - first - 1);
  if (hemisphere != "N" && hemisphere != "S") Fail(1, "--utm: hemisphere must be N or S");
  maps::Georeference g;
  auto* utm = g.mutable_utm();
  utm->set_zone(static_cast<int>(maps::cli::ParseInteger(kTool, "--utm", text.substr(0, first).c_str(), 1, 60)));
  utm->set_northern(hemisphere == "N");
  const auto offsets = ParseList("--utm", text.substr(second + 1), 2);
  utm->set_easting_offset_m(offsets[0]);
  utm->set_northing_offset_m(offsets[1]);
  return g;
}

BuildArgs ParseBuild(int argc, char** argv) {
  BuildArgs a;
  // The source's builder settings first, so that the flags override them.
  for (int i = 0; i < argc; ++i) {
    if (std::string_view(argv[i]) == "--carmen") a.builder = localization::mapping::LaserLogBuilderOptions();
  }
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto number = [&] { return maps::cli::ParseNumber(kTool, arg, value()); };
    if (arg == "--carmen") a.carmen = value();
    else if (arg == "--mode") value();  // grid: BuildMode() sent the others elsewhere
    else if (arg == "--pcap") a.pcap = value();
    else if (arg == "--can") a.can = value();
    else if (arg == "--dbc") a.dbc = value();
    else if (arg == "--odometry") a.odometry = value();
    else if (arg == "--config") a.config = value();
    else if (arg == "--anchor") a.anchor = value();
    else if (arg == "--scale-from") a.scale_from = value();
    else if (arg == "--scale-from-gnss") a.scale_from_gnss = true;
    else if (arg == "--out") a.out = value();
    else if (arg == "--png") a.png = value();
    else if (arg == "--trajectory") a.trajectory = value();
    else if (arg == "--odometry-out") a.odometry_out = value();
    else if (arg == "--calibrated-odometry-out") a.calibrated_odometry_out = value();
    else if (arg == "--reference-out") a.reference_out = value();
    else if (arg == "--json") a.json = true;
    else if (arg == "--seed") a.noise.seed = static_cast<std::uint64_t>(maps::cli::ParseInteger(kTool, arg, value(), 0, INT64_MAX));
    else if (arg == "--noise-translation") a.noise.translation_fraction = number();
    else if (arg == "--noise-lateral") a.noise.lateral_fraction = number();
    else if (arg == "--noise-rotation") a.noise.rotation_fraction = number();
    else if (arg == "--noise-rotation-per-m") a.noise.rotation_per_metre = number();
    else if (arg == "--noise-scale") a.noise.scale_sigma = number();
    else if (arg == "--keyframe-distance") a.builder.keyframe_distance_m = number();
    else if (arg == "--keyframe-angle") a.builder.keyframe_angle_rad = number();
    else if (arg == "--loop-radius") a.builder.loop_radius_m = number();
    else if (arg == "--loop-min-path") a.builder.loop_min_path_m = number();
    else if (arg == "--loop-min-score") a.builder.loop_min_score = number();
    else if (arg == "--loop-candidates") a.builder.loop_candidates = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 100));
    else if (arg == "--local-map-keyframes") a.builder.local_map_keyframes = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 1000));
    else if (arg == "--refine-sweeps") a.builder.refine_sweeps = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 10));
    else if (arg == "--scale-estimate") {
      const std::string_view v = value();
      if (v != "on" && v != "off") Fail(1, "--scale-estimate takes on or off");
      a.builder.estimate_odometry_scale = v == "on";
    } else if (arg == "--odometry-scale") a.builder.odometry_scale = number();
    else if (arg == "--map-min-votes") a.builder.map_min_votes = static_cast<std::size_t>(maps::cli::ParseInteger(kTool, arg, value(), 1, 100));
    else if (arg == "--odometry-sigma") {
      const auto v = ParseList(arg, value(), 3);
      a.odometry_sigma = localization::mapping::OdometryNoiseModel{v[0], v[0], v[1], v[2], 0.0, 0};
    } else if (arg == "--match-floor-m") a.builder.match_sigma_floor_m = number();
    else if (arg == "--match-floor-rad") a.builder.match_sigma_floor_rad = number();
    else if (arg == "--resolution") a.resolution_m = number();
    else if (arg == "--max-scans") a.max_scans = maps::cli::ParseInteger(kTool, arg, value(), 2, INT64_MAX);
    else if (arg == "--tile-cells") a.tile_cells = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 16, maps::kMaxTileCells));
    else if (arg == "--viewpoint-spacing") a.viewpoint_spacing_m = number();
    else if (arg == "--viewpoint-range") a.viewpoint_range_m = number();
    else if (arg == "--enu") {
      const auto v = ParseList(arg, value(), 3);
      auto* enu = a.georeference.mutable_enu();
      enu->set_latitude_deg(v[0]);
      enu->set_longitude_deg(v[1]);
      enu->set_altitude_m(v[2]);
    } else if (arg == "--utm") a.georeference = ParseUtm(value());
    else if (arg == "--help" || arg == "-h") {
      std::cout << kGridBuildUsage;
      std::exit(0);
    } else Fail(1, "build: unknown argument " + std::string(arg) + "\n" + kGridBuildUsage);
  }
  if (a.out.empty()) Fail(1, "build needs --out MAP");
  if (a.carmen.has_value() == a.pcap.has_value()) Fail(1, "build needs exactly one of --carmen and --pcap");
  if (a.pcap && (!a.can || !a.dbc || !a.odometry)) Fail(1, "build --pcap needs --can, --dbc and --odometry");
  if (a.carmen && (a.anchor || a.scale_from || a.scale_from_gnss)) {
    Fail(1, "--anchor, --scale-from and --scale-from-gnss are for drives (--pcap)");
  }
  if (a.scale_from && a.scale_from_gnss) Fail(1, "give one of --scale-from and --scale-from-gnss");
  if (a.carmen && a.calibrated_odometry_out) Fail(1, "--calibrated-odometry-out is for drives (--pcap)");
  if (!(a.resolution_m > 0.0) || !(a.viewpoint_range_m > 0.0) || a.viewpoint_spacing_m < 0.0 ||
      !(a.builder.keyframe_distance_m >= 0.0)) {
    Fail(1, "--resolution and --viewpoint-range must be positive, --viewpoint-spacing and --keyframe-distance >= 0");
  }
  if (!(a.builder.odometry_scale > 0.5 && a.builder.odometry_scale < 2.0)) Fail(1, "--odometry-scale must be within (0.5, 2)");
  a.builder.odometry = a.odometry_sigma.value_or(a.carmen ? a.noise : kDriveOdometrySigma);
  return a;
}

// What both sources hand to the writer.
struct BuiltMap {
  maps::ClassGrid mosaic{maps::GridGeometry{}};
  std::vector<TimedPose> estimate, odometry, reference;
  std::vector<localization::mapping::Keyframe> keyframes;
  localization::mapping::MapBuilderStats stats;
  double track_scale = 1.0;  // --scale-from's
  int track_scale_fixes = 0;
  std::string source;
};

BuiltMap BuildCarmen(const BuildArgs& a) {
  auto log = hal::carmen::ReadCarmenLaserScans(*a.carmen);
  if (!log.ok()) Fail(2, log.error().message);
  if (a.max_scans > 0 && log->scans.size() > static_cast<std::size_t>(a.max_scans)) {
    log->scans.resize(static_cast<std::size_t>(a.max_scans));
  }
  localization::mapping::CarmenBuildOptions options;
  options.builder = a.builder;
  options.noise = a.noise;
  options.mosaic_resolution_m = a.resolution_m;
  auto built = localization::mapping::BuildFromCarmen(log->scans, options);
  if (!built.ok()) Fail(3, built.error().message);
  BuiltMap out;
  out.mosaic = std::move(built->mosaic);
  out.estimate = std::move(built->estimate);
  out.odometry = std::move(built->odometry);
  out.reference = std::move(built->reference);
  out.keyframes = std::move(built->keyframes);
  out.stats = built->stats;
  out.source = "carmen " + *a.carmen + ", odometry noise seed " + std::to_string(a.noise.seed);
  return out;
}

BuiltMap BuildDrive(const BuildArgs& a) {
  localization::DriveBuildOptions options;
  options.capture = *a.pcap;
  options.can_log = *a.can;
  options.dbc = *a.dbc;
  options.odometry_config = *a.odometry;
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(localization::ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  options.grid = *grid;
  options.builder = a.builder;
  options.builder.point_range_m = std::min(options.builder.point_range_m, grid->size_m() / 2.0);
  if (a.anchor) {
    auto anchor = localization::evaluation::ReadTrajectory(*a.anchor);
    if (!anchor.ok()) Fail(2, anchor.error().message);
    options.anchor = std::move(*anchor);
  }
  if (a.scale_from) {
    auto track = localization::evaluation::ReadTrajectory(*a.scale_from);
    if (!track.ok()) Fail(2, track.error().message);
    options.scale_track = std::move(*track);
  }
  if (a.scale_from_gnss) {
    auto track = localization::ReadGnssTrack(*a.pcap);
    if (!track.ok()) Fail(2, track.error().message);
    if (track->size() < 3) Fail(2, *a.pcap + ": fewer than 3 valid GNSS fixes in its position packets");
    options.scale_track = std::move(*track);
  }
  auto built = localization::BuildFromDrive(options);
  if (!built.ok()) Fail(2, built.error().message);
  if (!built->mosaic) Fail(3, *a.pcap + ": no complete revolution within the CAN log's time: nothing to map");
  BuiltMap out;
  out.mosaic = std::move(*built->mosaic);
  out.estimate = std::move(built->estimate);
  out.odometry = std::move(built->odometry);
  out.keyframes = std::move(built->keyframes);
  out.stats = built->stats;
  out.track_scale = built->track_scale;
  out.track_scale_fixes = built->track_scale_fixes;
  out.source = "drive " + *a.pcap + " + " + *a.can;
  return out;
}

void WriteTrajectoryOrFail(const std::vector<TimedPose>& trajectory, const std::optional<std::string>& path) {
  if (!path) return;
  if (Status s = localization::evaluation::WriteTrajectory(trajectory, *path); !s.ok()) Fail(2, s.error().message);
}

}  // namespace

int GridBuildCommand(int argc, char** argv) {
  const BuildArgs a = ParseBuild(argc, argv);
  BuiltMap map = a.carmen ? BuildCarmen(a) : BuildDrive(a);
  localization::tools::MapOutputOptions output;
  output.write.tile_cells = a.tile_cells;
  output.write.georeference = a.georeference;
  output.write.created_by = "flat2d-map build (flat2d " FLAT2D_VERSION ")";
  output.write.source = map.source;
  output.viewpoint_spacing_m = a.viewpoint_spacing_m;
  output.viewpoint_range_m = a.viewpoint_range_m;
  if (a.png) output.png = *a.png;
  const auto written_map = localization::tools::WriteBuiltMap(std::move(map.mosaic), map.keyframes, map.estimate, a.out, output);
  if (!written_map.ok()) Fail(2, written_map.error().message);
  const std::size_t viewpoints = written_map->viewpoints;
  WriteTrajectoryOrFail(map.estimate, a.trajectory);
  WriteTrajectoryOrFail(map.odometry, a.odometry_out);
  if (a.calibrated_odometry_out) {
    const Status written = localization::WriteCalibratedOdometry(*a.odometry, map.stats.odometry_scale,
                                                                 map.track_scale, *a.calibrated_odometry_out);
    if (!written.ok()) Fail(2, written.error().message);
  }
  WriteTrajectoryOrFail(map.reference, a.reference_out);

  auto reader = maps::PriorMapReader::Open(a.out, 1);
  if (!reader.ok()) Fail(2, reader.error().message);
  const maps::PriorMapSummary summary = maps::SummarizePriorMap(*reader);
  const auto& st = map.stats;
  if (a.json) {
    std::printf("{\"map\":%s,\"scans\":%llu,\"keyframes\":%llu,\"tracking_accepted\":%llu,\"tracking_rejected\":%llu,"
                "\"loop_candidates\":%llu,\"loop_closures\":%llu,\"loop_closures_switched_off\":%llu,"
                "\"loop_closures_gated\":%llu,\"loop_closures_drift\":%llu,\"optimizations\":%llu,\"optimize_seconds\":%.3f,\"match_seconds\":%.3f,\"viewpoints\":%zu,"
                "\"odometry_scale\":%.6f,\"track_scale\":%.6f,\"track_scale_fixes\":%d}\n",
                maps::SummaryJson(summary).c_str(), static_cast<unsigned long long>(st.scans),
                static_cast<unsigned long long>(st.keyframes), static_cast<unsigned long long>(st.tracking_accepted),
                static_cast<unsigned long long>(st.tracking_rejected), static_cast<unsigned long long>(st.loop_candidates),
                static_cast<unsigned long long>(st.loop_accepted), static_cast<unsigned long long>(st.loop_switched_off),
                static_cast<unsigned long long>(st.loop_gated), static_cast<unsigned long long>(st.loop_drift_closed),
                static_cast<unsigned long long>(st.optimizations), st.optimize_seconds, st.match_seconds,
                viewpoints, st.odometry_scale, map.track_scale, map.track_scale_fixes);
  } else {
    std::printf("%s: %llu scans, %llu keyframes; tracking %llu accepted, %llu rejected; loop closures %llu of %llu "
                "candidates (%llu switched off by the robust mixture); odometry scale %.4f; %zu viewpoints\n",
                a.out.c_str(), static_cast<unsigned long long>(st.scans), static_cast<unsigned long long>(st.keyframes),
                static_cast<unsigned long long>(st.tracking_accepted), static_cast<unsigned long long>(st.tracking_rejected),
                static_cast<unsigned long long>(st.loop_accepted), static_cast<unsigned long long>(st.loop_candidates),
                static_cast<unsigned long long>(st.loop_switched_off), st.odometry_scale, viewpoints);
    if (map.track_scale_fixes > 0) {
      std::printf("scale from %d GNSS fixes: %.6f (wheels %.6f)\n", map.track_scale_fixes, map.track_scale,
                  st.odometry_scale * map.track_scale);
    }
    std::printf("%s", maps::SummaryText(summary).c_str());
  }
  return 0;
}

}  // namespace flat2d::localization::tools
