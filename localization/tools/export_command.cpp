#include "localization/tools/export_command.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/cloud/pcd_writer.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/evaluation/trajectory_error_3d.hpp"
#include "localization/tools/deskewed_drive.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kExportUsage = R"(
export DRIVE --out DIR --can LOG --dbc DBC --odometry CONFIG: a Velodyne capture's complete
revolutions, each deskewed by the CAN odometry into the sensor frame of its first fan, as
DIR/revolution_NNNNNN.pcd (x y z, binary; N counts the revolutions the odometry
covers, from 0), and DIR/sensor_poses.tum: world_T_sensor at each written revolution's
first fan, in file order. Deskewed points leave their lasers' cones: register the files
with `register --sensor MODEL` (auto-detection would take them as unorganized).
  --truth FILE.tum      the poses from this track of world_T_vehicle (the simulator's
                        truth.tum), interpolated; default: the dead-reckoned odometry
  --config FILE         StructureGridOptions: the sensor mounting (default: the shipped
                        structure_grid.textproto)
  --every N             every N-th complete revolution (default 1)
  --with-next           with each of those the revolution after it too: consecutive pairs
  --max-frames N        only the first N complete revolutions
  --json                a summary: revolutions, written, points, sensor
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";
constexpr TimeNs kMaxTruthGapNs = 200'000'000;  // the simulator writes its truth at 100 Hz

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::string out;
  std::optional<std::string> config, truth;
  DeskewedDriveOptions walk;  // the capture, CAN odometry files and revolution limit as given
  int every = 1;
  bool with_next = false;
  bool json = false;
};

int IntegerOption(int argc, char** argv, int& i, std::string_view flag) {
  return static_cast<int>(maps::cli::ParseInteger(kTool, flag, maps::cli::OptionValue(kTool, argc, argv, i), 1, 1 << 30));
}

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return std::string(maps::cli::OptionValue(kTool, argc, argv, i)); };
    if (arg == "--out") a.out = value();
    else if (arg == "--can") a.walk.can_log = value();
    else if (arg == "--dbc") a.walk.dbc = value();
    else if (arg == "--odometry") a.walk.odometry_config = value();
    else if (arg == "--config") a.config = value();
    else if (arg == "--truth") a.truth = value();
    else if (arg == "--every") a.every = IntegerOption(argc, argv, i, arg);
    else if (arg == "--with-next") a.with_next = true;
    else if (arg == "--max-frames") a.walk.max_revolutions = IntegerOption(argc, argv, i, arg);
    else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("--") && a.walk.capture.empty()) a.walk.capture = std::string(arg);
    else Fail(1, "export: unknown argument " + std::string(arg) + "\n" + kExportUsage);
  }
  if (a.walk.capture.empty() || a.out.empty()) Fail(1, std::string("export needs DRIVE and --out DIR\n") + kExportUsage);
  if (a.walk.can_log.empty() || a.walk.dbc.empty() || a.walk.odometry_config.empty()) {
    Fail(1, "export: deskewing needs CAN odometry: --can LOG --dbc DBC --odometry CONFIG");
  }
  return a;
}

// Writes each revolution as it comes and gathers the sensor's poses.
class RevolutionExporter {
 public:
  RevolutionExporter(const Args& args, const Eigen::Isometry3d& vehicle_T_sensor,
                     std::vector<hal::trajectory::StampedPose> truth)
      : args_(args), vehicle_T_sensor_(vehicle_T_sensor), truth_(std::move(truth)) {}

  void Add(const DeskewedRevolution& revolution) {
    const int index = seen_++;
    const bool chosen = index % args_.every == 0 || (args_.with_next && index % args_.every == 1);
    if (!chosen) return;
    Eigen::Isometry3d world_T_vehicle = revolution.world_T_vehicle;
    if (args_.truth) {
      const auto truth = evaluation::InterpolatedPose(truth_, revolution.stamp, kMaxTruthGapNs);
      if (!truth) Fail(2, *args_.truth + ": no pose at revolution " + std::to_string(index) + "'s time");
      world_T_vehicle = *truth;
    }
    char name[64];
    std::snprintf(name, sizeof name, "revolution_%06d.pcd", index);
    if (Status s = hal::cloud::WritePcd(std::filesystem::path(args_.out) / name, revolution.cloud); !s.ok()) {
      Fail(2, s.error().message);
    }
    poses_.push_back({revolution.stamp, world_T_vehicle * vehicle_T_sensor_});
    points_ += revolution.cloud.points.size();
    sensor_ = hal::velodyne::ModelName(revolution.model);
  }

  const std::vector<hal::trajectory::StampedPose>& poses() const { return poses_; }
  std::size_t points() const { return points_; }
  std::string_view sensor() const { return sensor_; }

 private:
  const Args& args_;
  const Eigen::Isometry3d vehicle_T_sensor_;
  const std::vector<hal::trajectory::StampedPose> truth_;
  std::vector<hal::trajectory::StampedPose> poses_;
  int seen_ = 0;
  std::size_t points_ = 0;
  std::string_view sensor_;
};

std::vector<hal::trajectory::StampedPose> ReadTruth(const Args& a) {
  if (!a.truth) return {};
  auto truth = hal::trajectory::ReadTum(*a.truth);
  if (!truth.ok()) Fail(2, truth.error().message);
  if (truth->size() < 2) Fail(2, *a.truth + ": fewer than 2 poses");
  return std::move(*truth);
}

}  // namespace

int ExportCommand(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  a.walk.vehicle_T_sensor = maps::VehicleFromSensor(grid->mounting());
  std::error_code error;
  std::filesystem::create_directories(a.out, error);
  if (error) Fail(2, a.out + ": cannot create (" + error.message() + ")");
  RevolutionExporter exporter(a, a.walk.vehicle_T_sensor, ReadTruth(a));
  auto walked = WalkDeskewedDrive(a.walk, [&](const DeskewedRevolution& r) { exporter.Add(r); });
  if (!walked.ok()) Fail(2, walked.error().message);
  const std::filesystem::path poses = std::filesystem::path(a.out) / "sensor_poses.tum";
  if (Status s = hal::trajectory::WriteTum(exporter.poses(), poses); !s.ok()) Fail(2, s.error().message);
  if (a.json) {
    std::printf("{\"revolutions\": %d, \"revolutions_without_odometry\": %d, \"written\": %zu, \"points\": %zu, "
                "\"sensor\": \"%.*s\", \"poses\": \"%s\"}\n",
                walked->complete_revolutions, walked->revolutions_without_odometry, exporter.poses().size(),
                exporter.points(), static_cast<int>(exporter.sensor().size()), exporter.sensor().data(),
                a.truth ? "truth" : "odometry");
  } else {
    std::printf("%zu of %d revolutions (%.*s) written to %s, poses (%s) in sensor_poses.tum\n", exporter.poses().size(),
                walked->complete_revolutions, static_cast<int>(exporter.sensor().size()), exporter.sensor().data(),
                a.out.c_str(), a.truth ? "truth" : "odometry");
  }
  return 0;
}

}  // namespace flat2d::localization::tools
