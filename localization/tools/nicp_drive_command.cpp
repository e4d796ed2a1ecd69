#include "localization/tools/nicp_drive_command.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/cloud/kitti_sequence.hpp"
#include "hal/cloud/ply_writer.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/tools/nicp_drive_build.hpp"
#include "localization/tools/prior_map_output.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kNicpDriveUsage = R"(
build --mode nicp DRIVE --out DIR: a Velodyne capture (.pcap, .pcapng) or a KITTI sequence
directory (velodyne/NNNNNN.bin, times.txt). Each complete revolution is deskewed (KITTI scans
are taken as stored), made an organized range frame (spherical projection of the identified
model, statistics over R = 0.3 m) and tracked by NICP against the merged model of the
revolutions before (or the last keyframe revolution, a new one every metre or 0.1 rad).
Writes DIR/trajectory.tum (world_T_vehicle at each revolution's first fan), DIR/model.ply
(points and normals of every 10th revolution, every 16th point), DIR/map.f2m (the 2D prior
map: the capture gridded at the tracked poses; not for KITTI) and DIR/map.png; with a CAN
log also DIR/odometry.tum (the CAN odometry open loop from the same first pose); for a KITTI
sequence with poses.txt and calib.txt DIR/truth.tum (world_T_vehicle at each scan, from the
first scan's vehicle frame).
  --can LOG --dbc DBC --odometry CONFIG
                        CAN odometry, as for build --pcap: the guess of every pair and the
                        motion that deskews each revolution (default: the previous motion)
  --config FILE         StructureGridOptions: the sensor mounting and the map's grids
                        (default: the shipped structure_grid.textproto)
  --anchor FILE.tum     the first revolution starts at this track's pose (GNSS, the
                        simulator's truth.tum) and the --json summary adds the drift
                        against it (default: the odometry's pose, else the origin)
  --method M            nicp (default) or point-to-plane
  --iterations N        (default 10)
  --pyramid S,S,...     register each revolution level by level, coarse to fine, at 1/S of
                        the image's columns (every row kept), e.g. 8,4,2 (the thesis' 1/8,
                        1/4, 1/2) or 8,4,2,1; each S divides the 2160 columns (default 1:
                        one level, --iterations there)
  --pyramid-iterations N
                        iterations at each level of a pyramid (default 3)
  --min-inlier-share S  with --tracking model: a revolution whose NICP inliers are fewer
                        than share S of its points with normals has failed to register and
                        is not merged (default 0.2)
  --max-frames N        only the first N complete revolutions
  --keyframe-distance M --keyframe-angle RAD
                        with --tracking keyframe: a keyframe is kept until the sensor is M
                        metres or RAD radians from it (default 1, 0.1; 0, 0: revolution to
                        revolution)
  --tracking T          model (default): register each revolution to the merged model of
                        the ones before and merge it (thesis 5.1.4; the latest 1 M points
                        kept); keyframe: register it to the last keyframe revolution
  --no-deskew           take each revolution as measured from one place
  --inverse-depth-weights
                        scale each NICP pair by w_i w_j, w = 1/range (thesis Eq. 6.4, 6.7)
  --planar              keep the vehicle on the ground plane after every registration
                        (height, roll and pitch zero): flat ground
  --ground-clearance M  leave out points less than M above the vehicle's ground plane
                        (default 0.2; negative: keep them): lone ground rings pull NICP
                        towards standing still
  --ground-range M      ... but keep those within M of the sensor, where the rings are
                        dense enough for a plane: height, roll and pitch (default 4)
  --no-map              skip the map (the capture's second pass)
  --json                a summary: frames, failures, frame_ms_p50/p95 (statistics +
                        registration), registration_ms_p50, load_ms_p50 (the deskewed
                        cloud), model_points, method, sensor, deskew, guess,
                        guesses_without_odometry, grid_seconds, viewpoints,
                        tracked_distance_m, tracking (keyframe, frame or model); with
                        --anchor distance_m, drift_percent,
                        end_error_m, max_error_m, end_heading_error_deg (and odometry_*)
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

bool IsCapture(std::string_view path) { return path.ends_with(".pcap") || path.ends_with(".pcapng"); }

// A drive to track: a Velodyne capture or a KITTI sequence directory.
bool IsDrive(std::string_view path) { return IsCapture(path) || hal::cloud::IsKittiSequence(std::filesystem::path(path)); }

// "8,4,2": column divisors, coarse to fine, each dividing the image's columns.
std::vector<int> ParsePyramid(std::string_view flag, const std::string& text, int columns) {
  const std::vector<int> scales = maps::cli::ParseCoarseToFine(kTool, flag, text, columns);
  for (const int scale : scales) {
    if (columns % scale != 0) {
      Fail(1, std::string(flag) + ": " + std::to_string(scale) + " does not divide the image's " +
                  std::to_string(columns) + " columns");
    }
  }
  return scales;
}

}  // namespace

bool ParseNicpDriveFlag(int argc, char** argv, int& i, NicpDriveArgs& a) {
  const std::string_view arg = argv[i];
  auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
  auto integer = [&](std::int64_t max) { return static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, max)); };
  if (arg == "--mode") value();  // checked by the caller
  else if (arg == "--out") a.out = value();
  else if (arg == "--can") a.options.can_log = value();
  else if (arg == "--dbc") a.options.dbc = value();
  else if (arg == "--odometry") a.options.odometry_config = value();
  else if (arg == "--config") a.config = value();
  else if (arg == "--anchor") a.anchor = value();
  else if (arg == "--method") {
    const auto method = registration::ParseMethod(value());
    if (!method) Fail(1, "build DRIVE: --method is nicp or point-to-plane");
    a.options.method = *method;
  } else if (arg == "--iterations") a.options.nicp.iterations = integer(1000);
  else if (arg == "--pyramid") a.options.lidar_pyramid = ParsePyramid(arg, value(), a.options.frames.lidar_columns);
  else if (arg == "--pyramid-iterations") a.options.pyramid_iterations = integer(1000);
  else if (arg == "--min-inlier-share") {
    a.options.min_inlier_share = static_cast<float>(maps::cli::ParseNumberIn(kTool, arg, value(), 0.0, 1.0));
  } else if (arg == "--max-frames") a.options.max_revolutions = integer(1 << 30);
  else if (arg == "--no-deskew") a.options.deskew = false;
  else if (arg == "--inverse-depth-weights") a.options.nicp.inverse_depth_weights = true;
  else if (arg == "--planar") a.options.planar = true;
  else if (arg == "--ground-clearance") a.options.ground_clearance_m = maps::cli::ParseNumber(kTool, arg, value());
  else if (arg == "--ground-range") a.options.ground_range_m = maps::cli::ParseNumber(kTool, arg, value());
  else if (arg == "--no-map") a.options.build_map = false;
  else if (arg == "--json") a.json = true;
  else if (IsDrive(arg) && a.options.capture.empty()) {
    a.options.capture = std::string(arg);
    // The structure grid's gridder works on Velodyne fans: a KITTI sequence gets no 2D map;
    // its scans are stored as measured (KITTI's odometry scans carry no firing times).
    if (!IsCapture(arg)) a.options.build_map = a.options.deskew = false;
  } else return false;
  return true;
}

void CheckNicpDriveArgs(const NicpDriveArgs& a, const std::string& mode, const char* usage) {
  if (a.options.capture.empty() || a.out.empty()) Fail(1, "build --mode " + mode + " needs DRIVE and --out DIR\n" + usage);
  const bool can = a.options.can_log.has_value();
  if (can != a.options.dbc.has_value() || can != a.options.odometry_config.has_value()) {
    Fail(1, "build --mode " + mode + " DRIVE: --can, --dbc and --odometry go together");
  }
}

namespace {

using Args = NicpDriveArgs;

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (ParseNicpDriveFlag(argc, argv, i, a)) continue;
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    if (arg == "--tracking") {
      const std::string_view tracking = value();
      if (tracking != "model" && tracking != "keyframe") Fail(1, "build --mode nicp DRIVE: --tracking is model or keyframe");
      a.options.frame_to_model = tracking == "model";
    } else if (arg == "--keyframe-distance") a.options.keyframe_distance_m = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--keyframe-angle") a.options.keyframe_angle_rad = maps::cli::ParseNumber(kTool, arg, value());
    else Fail(1, "build --mode nicp DRIVE: unknown argument " + std::string(arg) + "\n" + kNicpDriveUsage);
  }
  CheckNicpDriveArgs(a, "nicp", kNicpDriveUsage);
  return a;
}

}  // namespace

void PrepareNicpDrive(NicpDriveArgs& a) {
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  a.options.grid = *grid;
  if (a.anchor) {
    auto anchor = evaluation::ReadTrajectory(*a.anchor);
    if (!anchor.ok()) Fail(2, anchor.error().message);
    if (anchor->empty()) Fail(2, *a.anchor + ": no pose");
    a.options.anchor = std::move(*anchor);
  }
}

namespace {

// Writes the files; returns the map's viewpoints.
std::size_t WriteOutputs(const Args& a, NicpDriveResult& r) {
  const std::filesystem::path out = a.out;
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) Fail(2, a.out + ": cannot create (" + error.message() + ")");
  if (Status s = hal::trajectory::WriteTum(r.trajectory, out / "trajectory.tum"); !s.ok()) Fail(2, s.error().message);
  if (!r.odometry.empty()) {
    if (Status s = hal::trajectory::WriteTum(r.odometry, out / "odometry.tum"); !s.ok()) Fail(2, s.error().message);
  }
  if (!r.truth.empty()) {
    if (Status s = hal::trajectory::WriteTum(r.truth, out / "truth.tum"); !s.ok()) Fail(2, s.error().message);
  }
  if (Status s = hal::cloud::WritePly(out / "model.ply", r.model_points, r.model_normals); !s.ok()) Fail(2, s.error().message);
  if (!a.options.build_map) return 0;
  if (!r.mosaic) Fail(3, a.options.capture.string() + ": no revolution gridded at the tracked poses: nothing to map");
  auto written = WriteTrajectoryMap(std::move(*r.mosaic), r.trajectory, out, "flat2d-map build --mode nicp (flat2d " FLAT2D_VERSION ")",
                                    "drive " + a.options.capture.string() + ", NICP revolution to revolution");
  if (!written.ok()) Fail(2, written.error().message);
  return written->viewpoints;
}


void PrintDrift(const char* prefix, const Drift& d) {
  std::printf(", \"%sdrift_percent\": %.4f, \"%send_error_m\": %.4f, \"%smax_error_m\": %.4f, "
              "\"%send_heading_error_deg\": %.4f",
              prefix, d.percent(), prefix, d.end_error_m, prefix, d.max_error_m, prefix, d.end_heading_error_deg);
}

}  // namespace

double PathLength(const std::vector<hal::trajectory::StampedPose>& trajectory) {
  double length = 0.0;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    length += (trajectory[i].world_T_body.translation() - trajectory[i - 1].world_T_body.translation()).norm();
  }
  return length;
}

bool IsDriveBuild(int argc, char** argv) {
  // The flags of either mode that take no value.
  constexpr std::array<std::string_view, 6> kSwitches{"--json", "--no-deskew", "--no-map", "--planar", "--identity-guess",
                                                      "--inverse-depth-weights"};
  for (int i = 0; i < argc; ++i) {
    const std::string_view before = i > 0 ? argv[i - 1] : "";
    const bool option_value = before.starts_with("--") && std::find(kSwitches.begin(), kSwitches.end(), before) == kSwitches.end();
    if (IsDrive(argv[i]) && !option_value) return true;
  }
  return false;
}

int NicpDriveCommand(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  PrepareNicpDrive(a);
  auto tracked = TrackDriveByNicp(a.options);
  if (!tracked.ok()) Fail(2, tracked.error().message);
  NicpDriveResult& r = *tracked;
  const std::size_t viewpoints = WriteOutputs(a, r);
  const auto frame = evaluation::PercentilesOf(r.frame_ms);
  const double registration_p50 = evaluation::PercentilesOf(r.registration_ms).p50;
  const double load_p50 = evaluation::PercentilesOf(r.load_ms).p50;
  if (!a.json) {
    std::printf("%d revolutions (%s) tracked, %d failed registrations\n", r.frames, r.sensor.c_str(), r.failures);
    std::printf("per revolution: %.1f ms p50, %.1f ms p95 (statistics + registration); registration %.1f ms p50; "
                "deskewed cloud %.1f ms p50; map gridded in %.1f s\n",
                frame.p50, frame.p95, registration_p50, load_p50, r.grid_seconds);
    std::printf("wrote %s/trajectory.tum, model.ply (%zu points)%s\n", a.out.c_str(), r.model_points.size(),
                a.options.build_map ? ", map.f2m, map.png" : "");
    return 0;
  }
  std::printf("{\"frames\": %d, \"failures\": %d, \"frame_ms_p50\": %.3f, \"frame_ms_p95\": %.3f, "
              "\"registration_ms_p50\": %.3f, \"load_ms_p50\": %.3f, \"model_points\": %zu, \"method\": \"%s\", "
              "\"sensor\": \"%s\", \"deskew\": %s, \"guess\": \"%s\", \"guesses_without_odometry\": %d, "
              "\"grid_seconds\": %.3f, \"viewpoints\": %zu, \"tracked_distance_m\": %.3f, \"tracking\": \"%s\"",
              r.frames, r.failures, frame.p50, frame.p95, registration_p50, load_p50, r.model_points.size(),
              std::string(registration::MethodName(a.options.method)).c_str(), r.sensor.c_str(),
              a.options.deskew ? "true" : "false", a.options.can_log ? "can" : "constant-velocity",
              r.guesses_without_odometry, r.grid_seconds, viewpoints, PathLength(r.trajectory),
              a.options.frame_to_model                                                    ? "model"
              : a.options.keyframe_distance_m > 0.0 || a.options.keyframe_angle_rad > 0.0 ? "keyframe"
                                                                                          : "frame");
  if (!a.options.anchor.empty()) {
    const Drift nicp = DriftAgainst(a.options.anchor, r.trajectory);
    std::printf(", \"distance_m\": %.3f", nicp.distance_m);
    PrintDrift("", nicp);
    if (!r.odometry.empty()) PrintDrift("odometry_", DriftAgainst(a.options.anchor, r.odometry));
  }
  std::printf("}\n");
  return 0;
}

}  // namespace flat2d::localization::tools
