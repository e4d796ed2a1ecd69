#include "localization/tools/landmark_drive_command.hpp"

#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>

#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/tools/landmark_drive_build.hpp"
#include "localization/tools/drift.hpp"
#include "localization/tools/prior_map_output.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kLandmarkDriveUsage = R"(
build --mode landmarks DRIVE --out DIR --can LOG --dbc DBC --odometry CONFIG: a Velodyne
capture mapped by 3D landmark SLAM (thesis 8.2): each complete revolution deskewed by the
CAN odometry, its lines and planes extracted (as `features`), associated with the landmarks
they are near or made new ones, and the graph of odometry and landmark factors optimized.
Writes DIR/trajectory.tum (world_T_vehicle at each revolution's first fan), DIR/odometry.tum
(the CAN odometry open loop from the same first pose), DIR/landmarks.json (planes: normal,
d, centroid, observations; lines: point, direction, observations), DIR/map.f2m (the 2D prior
map: the capture gridded at the optimized poses) and DIR/map.png.
  --config FILE         StructureGridOptions: the sensor mounting and the map's grids
                        (default: the shipped structure_grid.textproto)
  --features-config F   extraction options (default: the shipped features3d.textproto)
  --anchor FILE.tum     the first revolution starts at this track's pose (GNSS, the
                        simulator's truth.tum); the --json summary adds the drift against it
  --max-frames N        only the first N complete revolutions
  --no-map              skip the map (the capture's second pass)
  --json                a summary: revolutions, sensor, pose_nodes, plane_landmarks,
                        line_landmarks, plane_factors, line_factors, features_ms_p50,
                        slam_ms_p50, finish_ms, grid_seconds, viewpoints; with --anchor
                        distance_m, drift_percent, end_error_m, ... (and odometry_*)
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::string out;
  std::optional<std::string> can, dbc, odometry, config, features_config, anchor;
  LandmarkDriveOptions options;
  bool json = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return std::string(maps::cli::OptionValue(kTool, argc, argv, i)); };
    if (arg == "--mode") value();  // landmarks: checked by the caller
    else if (arg == "--out") a.out = value();
    else if (arg == "--can") a.can = value();
    else if (arg == "--dbc") a.dbc = value();
    else if (arg == "--odometry") a.odometry = value();
    else if (arg == "--config") a.config = value();
    else if (arg == "--features-config") a.features_config = value();
    else if (arg == "--anchor") a.anchor = value();
    else if (arg == "--max-frames") {
      a.options.max_revolutions = static_cast<int>(maps::cli::ParseInteger(kTool, arg, maps::cli::OptionValue(kTool, argc, argv, i), 1, 1 << 30));
    } else if (arg == "--no-map") a.options.build_map = false;
    else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("--") && a.options.capture.empty()) a.options.capture = std::string(arg);
    else Fail(1, "build --mode landmarks: unknown argument " + std::string(arg) + "\n" + kLandmarkDriveUsage);
  }
  if (a.options.capture.empty() || a.out.empty()) Fail(1, std::string("build --mode landmarks needs DRIVE and --out DIR\n") + kLandmarkDriveUsage);
  if (!a.can || !a.dbc || !a.odometry) {
    Fail(1, "build --mode landmarks: the landmark graph needs CAN odometry: --can LOG --dbc DBC --odometry CONFIG");
  }
  return a;
}

void Prepare(Args& a) {
  a.options.can_log = *a.can;
  a.options.dbc = *a.dbc;
  a.options.odometry_config = *a.odometry;
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  a.options.grid = *grid;
  auto features = maps::features3d::LoadFeatureOptions(a.features_config.value_or(ShippedFeaturesConfig()));
  if (!features.ok()) Fail(2, features.error().message);
  a.options.features = *features;
  if (a.anchor) {
    auto anchor = evaluation::ReadTrajectory(*a.anchor);
    if (!anchor.ok()) Fail(2, anchor.error().message);
    if (anchor->empty()) Fail(2, *a.anchor + ": no pose");
    a.options.anchor = std::move(*anchor);
  }
}

std::string Vec(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.4f, %.4f, %.4f]", v.x(), v.y(), v.z());
  return text;
}

void WriteLandmarks(const LandmarkDriveResult& r, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "{\"planes\": [";
  for (std::size_t i = 0; i < r.planes.size(); ++i) {
    const auto& p = r.planes[i];
    out << (i ? ", " : "") << "{\"normal\": " << Vec(p.plane.normal) << ", \"d\": " << p.plane.distance
        << ", \"centroid\": " << Vec(p.centroid) << ", \"observations\": " << p.observations << "}";
  }
  out << "], \"lines\": [";
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    const auto& l = r.lines[i];
    out << (i ? ", " : "") << "{\"point\": " << Vec(l.point) << ", \"direction\": " << Vec(l.direction)
        << ", \"observations\": " << l.observations << "}";
  }
  out << "]}\n";
  if (!out) Fail(2, path.string() + ": cannot write");
}

// Writes the files; returns the map's viewpoints.
std::size_t WriteOutputs(const Args& a, LandmarkDriveResult& r) {
  const std::filesystem::path out = a.out;
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) Fail(2, a.out + ": cannot create (" + error.message() + ")");
  if (Status s = hal::trajectory::WriteTum(r.trajectory, out / "trajectory.tum"); !s.ok()) Fail(2, s.error().message);
  if (Status s = hal::trajectory::WriteTum(r.odometry, out / "odometry.tum"); !s.ok()) Fail(2, s.error().message);
  WriteLandmarks(r, out / "landmarks.json");
  if (!a.options.build_map) return 0;
  if (!r.mosaic) Fail(3, a.options.capture.string() + ": no revolution gridded at the optimized poses: nothing to map");
  auto written = WriteTrajectoryMap(std::move(*r.mosaic), r.trajectory, out, "flat2d-map build --mode landmarks (flat2d " FLAT2D_VERSION ")",
                                    "drive " + a.options.capture.string() + ", 3D line and plane landmark SLAM");
  if (!written.ok()) Fail(2, written.error().message);
  return written->viewpoints;
}

void PrintDrift(const char* prefix, const Drift& d) {
  std::printf(", \"%sdrift_percent\": %.4f, \"%send_error_m\": %.4f, \"%smax_error_m\": %.4f", prefix, d.percent(), prefix,
              d.end_error_m, prefix, d.max_error_m);
}

}  // namespace

int LandmarkDriveCommand(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  Prepare(a);
  auto built = BuildLandmarkDrive(a.options);
  if (!built.ok()) Fail(2, built.error().message);
  LandmarkDriveResult& r = *built;
  const std::size_t viewpoints = WriteOutputs(a, r);
  const double features_p50 = evaluation::PercentilesOf(r.features_ms).p50;
  const double slam_p50 = evaluation::PercentilesOf(r.slam_ms).p50;
  const landmarks::LandmarkSlamStats& s = r.stats;
  if (!a.json) {
    std::printf("%d revolutions (%s): %d pose nodes, %zu plane and %zu line landmarks, %d plane and %d line factors\n",
                r.revolutions, r.sensor.c_str(), s.pose_nodes, r.planes.size(), r.lines.size(), s.plane_factors,
                s.line_factors);
    std::printf("per revolution: features %.1f ms p50, graph %.1f ms p50; final optimization %.0f ms; map gridded in %.1f s\n",
                features_p50, slam_p50, r.finish_ms, r.grid_seconds);
    std::printf("wrote %s/trajectory.tum, odometry.tum, landmarks.json%s\n", a.out.c_str(),
                a.options.build_map ? ", map.f2m, map.png" : "");
    return 0;
  }
  std::printf("{\"revolutions\": %d, \"revolutions_without_odometry\": %d, \"sensor\": \"%s\", \"pose_nodes\": %d, "
              "\"plane_landmarks\": %zu, \"line_landmarks\": %zu, \"plane_factors\": %d, \"line_factors\": %d, "
              "\"features_ms_p50\": %.3f, \"slam_ms_p50\": %.3f, \"finish_ms\": %.1f, \"grid_seconds\": %.3f, "
              "\"viewpoints\": %zu",
              r.revolutions, r.revolutions_without_odometry, r.sensor.c_str(), s.pose_nodes, r.planes.size(),
              r.lines.size(), s.plane_factors, s.line_factors, features_p50, slam_p50, r.finish_ms, r.grid_seconds,
              viewpoints);
  if (!a.options.anchor.empty()) {
    const Drift slam = DriftAgainst(a.options.anchor, r.trajectory);
    std::printf(", \"distance_m\": %.3f", slam.distance_m);
    PrintDrift("", slam);
    PrintDrift("odometry_", DriftAgainst(a.options.anchor, r.odometry));
  }
  std::printf("}\n");
  return 0;
}

}  // namespace flat2d::localization::tools
