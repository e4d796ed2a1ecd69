#include "localization/tools/calibrate_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "localization/tools/calibrate_run.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kCalibrateUsage = R"(
calibrate DRIVE [DRIVE2]: where the LiDAR sits on the vehicle (vehicle_T_sensor, thesis
6.2.2, Eq. 6.1-6.3). Roll, pitch and height from the ground plane under the sensor (every
10th revolution, medians; flat ground); x, y and yaw from motion: the drive's revolutions
tracked by NICP, their motions over every metre or 0.1 rad solved against the CAN
odometry's from the configured mounting as the guess, twice (the tracking run again with
the first estimate). Motion alone cannot give the height on planar drives: the output
says where each component came from. With DRIVE2, the same drive recorded by a second LiDAR: its own mounting and
sensor1_T_sensor2, the second drive's reconstruction (its first 30 revolutions) registered
to the first's (NICP, KD-tree mode), beside from_hand_eye, the two mountings composed. A DRIVE is a directory holding lidar.pcap, can.log and vehicle.dbc (as
flat2d-sim --out writes them) or a capture file with --can and --dbc.
  --can LOG --dbc DBC   DRIVE's CAN log and DBC when DRIVE is a capture file
  --can2 LOG --dbc2 DBC ... DRIVE2's
  --odometry CONFIG     the odometry configuration (default: the shipped simulator
                        vehicle's flat2d_sim.textproto)
  --config FILE         StructureGridOptions whose mounting is the guess (default: the
                        shipped structure_grid.textproto)
  --initial X,Y,Z,ROLL,PITCH,YAW
                        the guess instead (metres, degrees, Z-Y-X Euler angles)
  --initial2 X,Y,Z,ROLL,PITCH,YAW
                        DRIVE2's guess (default: DRIVE's)
  --passes N            tracking and solve rounds (default 2)
  --no-ground           all six components by motion (Eq. 6.3 alone); by default roll,
                        pitch and height come from the ground plane under the sensor
                        (flat ground), x, y and yaw from motion
  --no-odometry-scale   take the odometry's distances as they are; by default they are
                        scaled to the tracked ones first (the median over straight
                        intervals), as a wheel scale error of s passes for a lateral lever
                        arm of s times the turn radius
  --tracking T          model (default) or keyframe, as build --mode nicp (the merged
                        model loses its way on the VLP-32C ramps drive; keyframes do not)
  --pair-distance M --pair-angle RAD
                        a motion pair spans M metres or RAD radians of the vehicle's
                        motion (default 1, 0.1)
  --reconstruction-revolutions N
                        with DRIVE2: each reconstruction holds the first N revolutions
                        (default 30)
  --reconstruction-radius M
                        ... and its normals are fitted over M (default 0.5)
  --max-frames N        only the first N complete revolutions of each drive
  --json                one JSON object: vehicle_T_sensor (DRIVE's), sensors (per drive:
                        drive, sensor, frames, failures, pairs, inliers, iterations,
                        seconds, initial, vehicle_T_sensor, observable, sigma,
                        source (motion, ground or guess per component), ground
                        (roll_deg, pitch_deg, height_m, revolutions, tried),
                        odometry_scale,
                        rms_translation_m, rms_rotation_deg) and, with DRIVE2,
                        sensor_pairs (sensor1_T_sensor2, from_hand_eye, inliers,
                        iterations, chi2, points1, points2, seconds). A pose is
                        {x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg, matrix (4x4 rows)}.
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct DriveArgs {
  std::string path;
  std::optional<std::string> can, dbc;
  std::optional<Eigen::Isometry3d> initial;
};

struct Args {
  std::vector<DriveArgs> drives;
  std::optional<std::string> odometry, config;
  CalibrateOptions options;
  bool json = false;
};

Eigen::Isometry3d ParseMounting(std::string_view flag, const char* text) {
  const std::vector<double> v = maps::cli::ParseNumberList(kTool, flag, text, 6);
  return maps::VehicleFromSensor(std::span<const double, 6>(v.data(), 6));
}

Args ParseArgs(int argc, char** argv) {
  Args a;
  a.drives.resize(2);
  std::size_t positional = 0;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto number = [&] { return maps::cli::ParseNumber(kTool, arg, value()); };
    if (arg == "--can") a.drives[0].can = value();
    else if (arg == "--dbc") a.drives[0].dbc = value();
    else if (arg == "--can2") a.drives[1].can = value();
    else if (arg == "--dbc2") a.drives[1].dbc = value();
    else if (arg == "--odometry") a.odometry = value();
    else if (arg == "--config") a.config = value();
    else if (arg == "--initial") a.drives[0].initial = ParseMounting(arg, value());
    else if (arg == "--initial2") a.drives[1].initial = ParseMounting(arg, value());
    else if (arg == "--passes") a.options.passes = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 10));
    else if (arg == "--pair-distance") a.options.pair_distance_m = number();
    else if (arg == "--pair-angle") a.options.pair_angle_rad = number();
    else if (arg == "--max-frames") a.options.tracking.max_revolutions = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 2, 1 << 30));
    else if (arg == "--no-ground") a.options.use_ground = false;
    else if (arg == "--no-odometry-scale") a.options.scale_odometry = false;
    else if (arg == "--tracking") {
      const std::string_view tracking = value();
      if (tracking != "model" && tracking != "keyframe") Fail(1, "calibrate: --tracking is model or keyframe");
      a.options.tracking.frame_to_model = tracking == "model";
    }
    else if (arg == "--reconstruction-revolutions") a.options.reconstruction_revolutions = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 1 << 20));
    else if (arg == "--reconstruction-radius") a.options.reconstruction_radius_m = static_cast<float>(number());
    else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("--") && positional < 2) a.drives[positional++].path = std::string(arg);
    else Fail(1, "calibrate: unknown argument " + std::string(arg) + "\n" + kCalibrateUsage);
  }
  if (positional == 0) Fail(1, std::string("calibrate needs a DRIVE\n") + kCalibrateUsage);
  if (positional == 1 && (a.drives[1].can || a.drives[1].dbc || a.drives[1].initial)) {
    Fail(1, "calibrate: --can2, --dbc2 and --initial2 need a DRIVE2");
  }
  if (!(a.options.pair_distance_m > 0.0) || !(a.options.pair_angle_rad > 0.0)) {
    Fail(1, "calibrate: --pair-distance and --pair-angle must be positive");
  }
  a.drives.resize(positional);
  return a;
}

// A drive directory's files, or a capture with its --can and --dbc.
CalibrationDrive ResolveDrive(const DriveArgs& d, const Eigen::Isometry3d& initial, std::string_view suffix) {
  CalibrationDrive drive;
  drive.initial_vehicle_T_sensor = d.initial.value_or(initial);
  const std::filesystem::path path = d.path;
  if (std::filesystem::is_directory(path)) {
    if (d.can || d.dbc) Fail(1, "calibrate: " + d.path + " is a drive directory: its can.log and vehicle.dbc are used, not --can" + std::string(suffix));
    drive.capture = path / "lidar.pcap";
    drive.can_log = path / "can.log";
    drive.dbc = path / "vehicle.dbc";
    for (const auto& file : {drive.capture, drive.can_log, drive.dbc}) {
      if (!std::filesystem::exists(file)) Fail(2, file.string() + ": no such file (a drive directory holds lidar.pcap, can.log and vehicle.dbc)");
    }
    return drive;
  }
  if (!d.can || !d.dbc) Fail(1, "calibrate: " + d.path + " is a capture: give its --can" + std::string(suffix) + " and --dbc" + std::string(suffix));
  drive.capture = path;
  drive.can_log = *d.can;
  drive.dbc = *d.dbc;
  return drive;
}

void Prepare(Args& a) {
  auto grid = maps::LoadStructureGridOptions(a.config.value_or(ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  a.options.tracking.grid = *grid;
  a.options.odometry_config = a.odometry.value_or(ShippedSimOdometryConfig());
  const Eigen::Isometry3d configured = maps::VehicleFromSensor(grid->mounting());
  const Eigen::Isometry3d first = a.drives[0].initial.value_or(configured);
  for (std::size_t d = 0; d < a.drives.size(); ++d) {
    a.options.drives.push_back(ResolveDrive(a.drives[d], first, d == 0 ? "" : "2"));
  }
}

std::string PoseJson(const Eigen::Isometry3d& pose) {
  const maps::SensorMounting m = maps::MountingOf(pose);
  std::string json;
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "{\"x_m\": %.4f, \"y_m\": %.4f, \"z_m\": %.4f, \"roll_deg\": %.3f, \"pitch_deg\": %.3f, \"yaw_deg\": %.3f, \"matrix\": [",
                m.x_m(), m.y_m(), m.z_m(), m.roll_deg(), m.pitch_deg(), m.yaw_deg());
  json += buffer;
  for (int r = 0; r < 4; ++r) {
    const Eigen::Vector4d row = pose.matrix().row(r);
    std::snprintf(buffer, sizeof buffer, "%s[%.6f, %.6f, %.6f, %.6f]", r ? ", " : "", row[0], row[1], row[2], row[3]);
    json += buffer;
  }
  return json + "]}";
}

// Where each component comes from: "motion" (Eq. 6.3), "ground" (the ground plane) or
// "guess" (neither constrains it).
const char* SourceOf(const SensorCalibration& s, std::size_t k) {
  if (s.hand_eye.observable[k]) return "motion";
  const bool from_ground = s.ground && (k == 2 || k == 3 || k == 4);
  return from_ground ? "ground" : "guess";
}

std::string ComponentsJson(const SensorCalibration& s, const char* what) {
  std::string json = "{";
  for (std::size_t k = 0; k < calibration::kMountingComponents.size(); ++k) {
    char buffer[64];
    const char* name = calibration::kMountingComponents[k].data();
    const char* comma = k ? ", " : "";
    if (std::string_view(what) == "sigma") std::snprintf(buffer, sizeof buffer, "%s\"%s\": %.4f", comma, name, s.hand_eye.sigma[k]);
    else if (std::string_view(what) == "source") std::snprintf(buffer, sizeof buffer, "%s\"%s\": \"%s\"", comma, name, SourceOf(s, k));
    else std::snprintf(buffer, sizeof buffer, "%s\"%s\": %s", comma, name, s.hand_eye.observable[k] ? "true" : "false");
    json += buffer;
  }
  return json + "}";
}

std::string GroundJson(const std::optional<GroundEstimate>& g) {
  if (!g) return "null";
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "{\"roll_deg\": %.3f, \"pitch_deg\": %.3f, \"height_m\": %.4f, \"revolutions\": %d, \"tried\": %d}",
                g->roll_deg, g->pitch_deg, g->height_m, g->revolutions, g->tried);
  return buffer;
}

void PrintJson(const Args& a, const CalibrateResult& r) {
  std::printf("{\"vehicle_T_sensor\": %s, \"sensors\": [", PoseJson(r.sensors[0].hand_eye.vehicle_T_sensor).c_str());
  for (std::size_t d = 0; d < r.sensors.size(); ++d) {
    const SensorCalibration& s = r.sensors[d];
    const calibration::HandEyeResult& h = s.hand_eye;
    std::printf("%s{\"drive\": \"%s\", \"sensor\": \"%s\", \"frames\": %d, \"failures\": %d, \"pairs\": %d, \"inliers\": %d, "
                "\"iterations\": %d, \"seconds\": %.2f, \"initial\": %s, \"vehicle_T_sensor\": %s, \"observable\": %s, "
                "\"sigma\": %s, \"source\": %s, \"ground\": %s, \"odometry_scale\": %.5f, \"rms_translation_m\": %.4f, "
                "\"rms_rotation_deg\": %.4f}",
                d ? ", " : "", a.drives[d].path.c_str(), s.sensor.c_str(), s.frames, s.failures, h.pairs, h.inliers, h.iterations,
                s.seconds, PoseJson(a.options.drives[d].initial_vehicle_T_sensor).c_str(), PoseJson(h.vehicle_T_sensor).c_str(),
                ComponentsJson(s, "observable").c_str(), ComponentsJson(s, "sigma").c_str(), ComponentsJson(s, "source").c_str(),
                GroundJson(s.ground).c_str(), s.odometry_scale, h.rms_translation_m, h.rms_rotation_deg);
  }
  std::printf("]");
  if (r.pair) {
    const SensorPairCalibration& p = *r.pair;
    std::printf(", \"sensor_pairs\": [{\"sensor1_T_sensor2\": %s, \"from_hand_eye\": %s, \"inliers\": %d, \"iterations\": %d, "
                "\"chi2\": %.3f, \"points1\": %zu, \"points2\": %zu, \"seconds\": %.2f}]",
                PoseJson(p.sensor1_T_sensor2).c_str(), PoseJson(p.from_hand_eye).c_str(), p.inliers, p.iterations, p.chi2, p.points1,
                p.points2, p.seconds);
  }
  std::printf("}\n");
}

void PrintText(const Args& a, const CalibrateResult& r) {
  for (std::size_t d = 0; d < r.sensors.size(); ++d) {
    const calibration::HandEyeResult& h = r.sensors[d].hand_eye;
    const maps::SensorMounting m = maps::MountingOf(h.vehicle_T_sensor);
    std::printf("%s (%s, %d revolutions, %d of %d motion pairs inliers, rms %.3f m / %.3f deg):\n", a.drives[d].path.c_str(),
                r.sensors[d].sensor.c_str(), r.sensors[d].frames, h.inliers, h.pairs, h.rms_translation_m, h.rms_rotation_deg);
    std::printf("  mounting { x_m: %.4f y_m: %.4f z_m: %.4f roll_deg: %.3f pitch_deg: %.3f yaw_deg: %.3f }\n", m.x_m(), m.y_m(), m.z_m(),
                m.roll_deg(), m.pitch_deg(), m.yaw_deg());
    for (std::size_t k = 0; k < calibration::kMountingComponents.size(); ++k) {
      const std::string_view source = SourceOf(r.sensors[d], k);
      if (source == "ground") std::printf("  %s: from the ground plane\n", calibration::kMountingComponents[k].data());
      if (source == "guess") std::printf("  %s: not observable on this drive (kept from the guess)\n", calibration::kMountingComponents[k].data());
    }
  }
  if (r.pair) {
    const maps::SensorMounting m = maps::MountingOf(r.pair->sensor1_T_sensor2);
    std::printf("sensor1_T_sensor2: x %.4f y %.4f z %.4f m, roll %.3f pitch %.3f yaw %.3f deg (%d inliers)\n", m.x_m(), m.y_m(), m.z_m(),
                m.roll_deg(), m.pitch_deg(), m.yaw_deg(), r.pair->inliers);
  }
}

}  // namespace

int CalibrateCommand(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  Prepare(a);
  auto result = Calibrate(a.options);
  if (!result.ok()) {
    const std::string& message = result.error().message;
    Fail(message.starts_with("calibrate:") || message.find("hand-eye") != std::string::npos ? 3 : 2, message);
  }
  if (a.json) PrintJson(a, *result);
  else PrintText(a, *result);
  return 0;
}

}  // namespace flat2d::localization::tools
