// flat2d-peer-narf-slam: the landmark SLAM of `flat2d-map build --mode landmarks` fed with
// PCL's NARF key-points instead of flat2d's lines and planes (narf_slam_run.hpp), the
// comparison of thesis 8.2 (Fig. 8.5-8.6). Writes the trajectories; prints a summary, --json
// one object with build --mode landmarks' keys where they mean the same.
// Exit status: 0 ok, 1 usage, 2 a file cannot be read or written.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "localization/evaluation/relations.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/peers/narf_slam_run.hpp"
#include "localization/tools/drift.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;
using localization::peers::NarfSlamResult;

constexpr std::string_view kTool = "flat2d-peer-narf-slam";

constexpr const char* kUsage = R"(usage:
  flat2d-peer-narf-slam DRIVE.pcap --can LOG --dbc DBC --odometry CONFIG --out DIR [options]

The landmark SLAM of `flat2d-map build --mode landmarks` (same deskewing by the CAN
odometry, same back end and options) fed, per revolution, with PCL's NARF key-points as
point landmarks instead of lines and planes: a spherical range image of the revolution
(pcl::RangeImage), its borders (pcl::RangeImageBorderExtractor), pcl::NarfKeypoint.
Writes DIR/trajectory.tum (world_T_vehicle at each revolution's first fan) and
DIR/odometry.tum (the CAN odometry open loop from the same first pose).
  --config FILE         StructureGridOptions: the sensor mounting (default: the shipped
                        structure_grid.textproto)
  --anchor FILE.tum     the first revolution starts at this track's pose; the summary adds
                        the drift against it
  --max-frames N        only the first N complete revolutions
  --angular-resolution X,Y  the range image's degrees per pixel across and in elevation
                        (default 0.2,1.33: an HDL-32E's firing and laser spacing)
  --support-size M      NARF's support size in metres (default 1)
  --json                one object: revolutions, sensor image size, pose_nodes,
                        point_landmarks, point_factors, keypoints_per_revolution (mean),
                        keypoints_p50, keypoints_ms_p50, keypoints_ms_p95,
                        keypoints_cpu_ms_p50 (process CPU time), deskew_ms_p50,
                        slam_ms_p50, finish_ms; with --anchor distance_m, drift_percent,
                        end_error_m, max_error_m (and odometry_*)
Exit status: 0 ok, 1 usage, 2 a file cannot be read or written.
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::string out;
  std::optional<std::string> can, dbc, odometry, config, anchor;
  localization::peers::NarfSlamOptions options;
  bool json = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return std::string(maps::cli::OptionValue(kTool, argc, argv, i)); };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--out") a.out = value();
    else if (arg == "--can") a.can = value();
    else if (arg == "--dbc") a.dbc = value();
    else if (arg == "--odometry") a.odometry = value();
    else if (arg == "--config") a.config = value();
    else if (arg == "--anchor") a.anchor = value();
    else if (arg == "--max-frames") {
      a.options.drive.max_revolutions =
          static_cast<int>(maps::cli::ParseInteger(kTool, arg, maps::cli::OptionValue(kTool, argc, argv, i), 1, 1 << 30));
    } else if (arg == "--angular-resolution") {
      const std::vector<double> v = maps::cli::ParseNumberList(kTool, arg, value(), 2);
      if (!(v[0] > 0.0 && v[1] > 0.0)) Fail(1, "--angular-resolution: both must be positive");
      a.options.narf.angular_resolution_x_deg = v[0];
      a.options.narf.angular_resolution_y_deg = v[1];
    } else if (arg == "--support-size") {
      a.options.narf.support_size_m = maps::cli::ParseNumber(kTool, arg, maps::cli::OptionValue(kTool, argc, argv, i));
      if (!(a.options.narf.support_size_m > 0.0)) Fail(1, "--support-size must be positive");
    } else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("-") && a.options.drive.capture.empty()) a.options.drive.capture = std::string(arg);
    else Fail(1, "unknown argument " + std::string(arg) + " (see --help)");
  }
  if (a.options.drive.capture.empty() || a.out.empty()) Fail(1, "needs DRIVE and --out DIR (see --help)");
  if (!a.can || !a.dbc || !a.odometry) Fail(1, "needs the CAN odometry: --can LOG --dbc DBC --odometry CONFIG");
  return a;
}

void Prepare(Args& a) {
  localization::tools::DeskewedDriveOptions& drive = a.options.drive;
  drive.can_log = *a.can;
  drive.dbc = *a.dbc;
  drive.odometry_config = *a.odometry;
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(localization::ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  if (Status valid = maps::ValidateStructureGridOptions(*grid); !valid.ok()) Fail(2, valid.error().message);
  drive.vehicle_T_sensor = maps::VehicleFromSensor(grid->mounting());
  if (a.anchor) {
    auto anchor = localization::evaluation::ReadTrajectory(*a.anchor);
    if (!anchor.ok()) Fail(2, anchor.error().message);
    if (anchor->empty()) Fail(2, *a.anchor + ": no pose");
    drive.anchor = std::move(*anchor);
  }
}

// Open-loop drift against the anchor track, as build --mode landmarks reports it.
void PrintDrift(const char* prefix, const std::vector<localization::evaluation::TimedPose>& reference,
                const std::vector<hal::trajectory::StampedPose>& trajectory) {
  const localization::tools::Drift d = localization::tools::DriftAgainst(reference, trajectory);
  if (*prefix == '\0') std::printf(", \"distance_m\": %.3f", d.distance_m);
  std::printf(", \"%sdrift_percent\": %.4f, \"%send_error_m\": %.4f, \"%smax_error_m\": %.4f", prefix, d.percent(),
              prefix, d.end_error_m, prefix, d.max_error_m);
}

void WriteOutputs(const Args& a, const NarfSlamResult& r) {
  const std::filesystem::path out = a.out;
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) Fail(2, a.out + ": cannot create (" + error.message() + ")");
  if (Status s = hal::trajectory::WriteTum(r.trajectory, out / "trajectory.tum"); !s.ok()) Fail(2, s.error().message);
  if (Status s = hal::trajectory::WriteTum(r.odometry, out / "odometry.tum"); !s.ok()) Fail(2, s.error().message);
}

void PrintJson(const Args& a, const NarfSlamResult& r) {
  using localization::evaluation::PercentilesOf;
  std::vector<double> counts(r.keypoints.begin(), r.keypoints.end());
  double total = 0.0;
  for (const double c : counts) total += c;
  const localization::evaluation::ErrorPercentiles ms = PercentilesOf(r.keypoints_ms);
  const localization::landmarks::LandmarkSlamStats& s = r.stats;
  std::printf("{\"revolutions\": %d, \"revolutions_without_odometry\": %d, \"image_width\": %d, \"image_height\": %d, "
              "\"pose_nodes\": %d, \"point_landmarks\": %d, \"point_factors\": %d, \"associations\": %d, "
              "\"downweighted_factors\": %d, \"keypoints_per_revolution\": %.2f, \"keypoints_p50\": %.0f, "
              "\"keypoints_ms_p50\": %.3f, \"keypoints_ms_p95\": %.3f, \"keypoints_cpu_ms_p50\": %.3f, "
              "\"deskew_ms_p50\": %.3f, \"slam_ms_p50\": %.3f, \"finish_ms\": %.1f",
              r.revolutions, r.revolutions_without_odometry, r.image_width, r.image_height, s.pose_nodes,
              s.point_landmarks, s.point_factors, s.associations, s.downweighted_factors,
              total / static_cast<double>(std::max(r.revolutions, 1)), PercentilesOf(counts).p50, ms.p50, ms.p95,
              PercentilesOf(r.keypoints_cpu_ms).p50, PercentilesOf(r.deskew_ms).p50, PercentilesOf(r.slam_ms).p50, r.finish_ms);
  if (!a.options.drive.anchor.empty()) {
    PrintDrift("", a.options.drive.anchor, r.trajectory);
    PrintDrift("odometry_", a.options.drive.anchor, r.odometry);
  }
  std::printf("}\n");
}

}  // namespace

int main(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  Prepare(a);
  auto run = localization::peers::RunNarfSlam(a.options);
  if (!run.ok()) Fail(2, run.error().message);
  WriteOutputs(a, *run);
  if (a.json) {
    PrintJson(a, *run);
    return 0;
  }
  const NarfSlamResult& r = *run;
  std::printf("%d revolutions: %d pose nodes, %d point landmarks, %d point factors\n", r.revolutions,
              r.stats.pose_nodes, r.stats.point_landmarks, r.stats.point_factors);
  std::printf("per revolution: %.0f NARF key-points p50 in %.1f ms p50, graph %.1f ms p50; final optimization %.0f ms\n",
              localization::evaluation::PercentilesOf(std::vector<double>(r.keypoints.begin(), r.keypoints.end())).p50,
              localization::evaluation::PercentilesOf(r.keypoints_ms).p50,
              localization::evaluation::PercentilesOf(r.slam_ms).p50, r.finish_ms);
  std::printf("wrote %s/trajectory.tum, odometry.tum\n", a.out.c_str());
  return 0;
}
