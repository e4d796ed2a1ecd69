// flat2d-sim: simulate a drive through a world and write what the vehicle's sensors would
// have recorded (lidar.pcap, can.log, vehicle.dbc) with its ground truth (truth.tum,
// truth_map.pgm/.yaml/.png), or stream the LiDAR packets live to UDP.
// Exit status: 0 ok, 2 usage error (bad option, unknown world or sensor, drive out of
// range, unwritable output directory), 1 the simulation failed (e.g. a write error).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/net/ipv4.hpp"
#include "hal/sim/simulation.hpp"
#include "hal/sim/simulation_sinks.hpp"
#include "hal/sim/worlds.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/sim_report.hpp"

namespace {

using namespace flat2d;
using namespace flat2d::hal::sim;
namespace net = flat2d::hal::net;
namespace velodyne = flat2d::hal::velodyne;

constexpr const char* kUsage = R"(usage:
  flat2d-sim --world W --drive N --seed S --duration SECONDS --sensor MODEL --out DIR
  flat2d-sim --world W --drive N --udp HOST[:PORT] [--rate X]
  flat2d-sim --list [--json]

  --world W             built-in world (office, campus, ramps, occluders; see --list) or a
                        SceneDescription .textproto file (default campus)
  --drive N             index of the world's drive (default 0: the mapping drive)
  --seed S              seed of every random error (default 1); equal arguments, equal bytes
  --duration SECONDS    simulated time (default: the whole drive)
  --sensor MODEL        vlp16 | hdl32e | vlp32c (default hdl32e)
  --out DIR             write lidar.pcap, can.log, vehicle.dbc, truth.tum, truth_map.pgm,
                        truth_map.yaml, truth_map.png into DIR (created if missing)
  --udp HOST[:PORT]     also send the packets live to HOST at real time: data to PORT
                        (default 2368), position packets to --position-port (default 8308)
  --position-port P     position packet port (default 8308)
  --rate X              live speed factor (default 1: real time; 0: as fast as possible)
  --rotation-hz HZ      LiDAR rotation rate, 5-20 (default 10)
  --odometry-noise P    mems | fog | none (default mems)
  --mounting X,Y,Z,ROLL,PITCH,YAW
                        the LiDAR in the vehicle frame: metres and degrees, Z-Y-X Euler
                        angles as the structure grid's mounting (default 0,0,1.9,0,0,0);
                        two runs with one seed and different mountings are one drive seen
                        by two sensors (flat2d-map calibrate)
  --gnss                put noisy GNSS fixes ($GPRMC) into the position packets
  --gnss-rtk            ... from a survey (RTK) receiver: 2 cm per axis, not 1 m, and seven
                        decimals of minutes (implies --gnss)
  --truth-rate HZ       truth.tum rate, >= 100 (default 200)
  --map-resolution M    truth map cell size in metres (default 0.05; campus: 10080 x 6880 cells)
  --start UNIX_SECONDS  time of the drive's start (default 1767225600: 2026-01-01T00:00:00Z)
  --list                the built-in worlds and their drives with durations and lengths
  --json                one JSON object on stdout (the run's summary, or the list)
  --help                this text
)";

constexpr std::string_view kTool = "flat2d-sim";
constexpr int kUsageError = 2;
constexpr int kRunError = 1;

[[noreturn]] void Fail(int status, const std::string& message) {
  std::cerr << kTool << ": " << message << "\n";
  std::exit(status);
}

struct CliOptions {
  SimulationOptions simulation;
  std::string world = "campus";
  std::optional<std::string> out;
  FileSinkOptions files;
  std::optional<net::Ipv4Endpoint> udp;
  double rate = 1.0;
  bool list = false;
  bool json = false;
};

double ParseNumber(std::string_view flag, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value)) {
    Fail(kUsageError, std::string(flag) + ": not a number: " + text);
  }
  return value;
}

std::int64_t ParseInteger(std::string_view flag, const std::string& text, std::int64_t min,
                          std::int64_t max) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || value < min || value > max) {
    Fail(kUsageError, std::string(flag) + ": expected an integer from " + std::to_string(min) +
                          " to " + std::to_string(max) + ", got " + text);
  }
  return value;
}

std::uint64_t ParseSeed(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text[0] == '-' || *end != '\0' || errno != 0) {
    Fail(kUsageError, "--seed: expected a non-negative integer, got " + text);
  }
  return value;
}

// X,Y,Z,ROLL,PITCH,YAW (metres, degrees) as vehicle_T_sensor.
Eigen::Isometry3d ParseMounting(const std::string& text) {
  std::vector<double> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    values.push_back(ParseNumber("--mounting", text.substr(begin, comma - begin)));
    begin = comma + 1;
  }
  if (values.size() != 6) Fail(kUsageError, "--mounting: expected X,Y,Z,ROLL,PITCH,YAW, got " + text);
  return flat2d::maps::VehicleFromSensor(std::span<const double, 6>(values.data(), 6));
}

// HOST[:PORT] with a dotted-quad host.
net::Ipv4Endpoint ParseUdp(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string host = text.substr(0, colon);
  const auto address = net::ParseIpv4(host);
  if (!address) Fail(kUsageError, "--udp: not an IPv4 address: " + host);
  net::Ipv4Endpoint endpoint{*address, 2368};
  if (colon != std::string::npos) {
    endpoint.port = static_cast<std::uint16_t>(ParseInteger("--udp port", text.substr(colon + 1), 1, 65535));
  }
  return endpoint;
}

CliOptions ParseArguments(int argc, char** argv) {
  CliOptions options;
  std::optional<velodyne::Model> sensor;
  std::optional<double> rotation_hz;
  std::optional<Eigen::Isometry3d> mounting;
  bool gnss = false;
  bool gnss_rtk = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Fail(kUsageError, std::string(arg) + " needs a value");
      return argv[++i];
    };
    SimulationOptions& sim = options.simulation;
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--world") {
      options.world = value();
    } else if (arg == "--drive") {
      sim.drive = static_cast<int>(ParseInteger(arg, value(), 0, 1'000'000));
    } else if (arg == "--seed") {
      sim.seed = ParseSeed(value());
    } else if (arg == "--duration") {
      sim.duration_s = ParseNumber(arg, value());
      if (!(*sim.duration_s > 0.0)) Fail(kUsageError, "--duration must be positive");
    } else if (arg == "--sensor") {
      const std::string name = value();
      sensor = ParseSensorName(name);
      if (!sensor) Fail(kUsageError, "unknown sensor '" + name + "': use vlp16, hdl32e or vlp32c");
    } else if (arg == "--out") {
      options.out = value();
    } else if (arg == "--udp") {
      options.udp = ParseUdp(value());
    } else if (arg == "--position-port") {
      sim.position_port = static_cast<std::uint16_t>(ParseInteger(arg, value(), 1, 65535));
    } else if (arg == "--rate") {
      options.rate = ParseNumber(arg, value());
      if (options.rate < 0.0) Fail(kUsageError, "--rate must not be negative");
    } else if (arg == "--rotation-hz") {
      rotation_hz = ParseNumber(arg, value());
    } else if (arg == "--mounting") {
      mounting = ParseMounting(value());
    } else if (arg == "--odometry-noise") {
      const std::string name = value();
      const auto preset = OdometryNoisePreset(name);
      if (!preset) Fail(kUsageError, "unknown odometry noise '" + name + "': use mems, fog or none");
      sim.odometry_noise = *preset;
    } else if (arg == "--gnss") {
      gnss = true;
    } else if (arg == "--gnss-rtk") {
      gnss = gnss_rtk = true;
    } else if (arg == "--truth-rate") {
      sim.truth_rate_hz = ParseNumber(arg, value());
    } else if (arg == "--map-resolution") {
      options.files.truth_map_options.resolution_m = ParseNumber(arg, value());
      if (!(options.files.truth_map_options.resolution_m >= 0.01 &&
            options.files.truth_map_options.resolution_m <= 10.0)) {
        Fail(kUsageError, "--map-resolution must be 0.01-10 m");
      }
    } else if (arg == "--start") {
      sim.start_epoch_ns = ParseInteger(arg, value(), 0, 4'000'000'000) * kNsPerSecond;
    } else if (arg == "--list") {
      options.list = true;
    } else if (arg == "--json") {
      options.json = true;
    } else {
      Fail(kUsageError, "unknown argument " + std::string(arg) + "\n" + kUsage);
    }
  }
  SimulationOptions& sim = options.simulation;
  sim.lidar = DefaultLidarOptions(sensor.value_or(velodyne::Model::kHdl32e));
  if (rotation_hz) sim.lidar.rotation_hz = *rotation_hz;
  if (mounting) sim.lidar.vehicle_T_sensor = *mounting;
  sim.lidar.gnss.enabled = gnss;
  sim.lidar.gnss.rtk = gnss_rtk;
  if (Status valid = ValidateLidarOptions(sim.lidar); !valid) Fail(kUsageError, valid.error().message);
  if (options.udp) sim.data_port = options.udp->port;
  if (!options.list && !options.out && !options.udp) {
    Fail(kUsageError, std::string("nothing to do: give --out DIR and/or --udp HOST[:PORT]\n") + kUsage);
  }
  return options;
}

int List(bool json) {
  std::vector<maps::sim_cli::WorldListing> worlds;
  for (const std::string_view view : BuiltInWorldNames()) {
    const std::string name(view);
    auto world = ResolveWorld(name);
    if (!world.ok()) Fail(kRunError, world.error().message);
    auto drives = DescribeDrives(*world);
    if (!drives.ok()) Fail(kRunError, "world " + name + ": " + drives.error().message);
    worlds.push_back({name, world->description(), std::move(*drives)});
  }
  std::cout << (json ? maps::sim_cli::ListToJson(worlds) : maps::sim_cli::ListToText(worlds));
  return 0;
}

int Simulate(CliOptions& options) {
  auto world = ResolveWorld(options.world);
  if (!world.ok()) Fail(kUsageError, world.error().message);
  const int drives = world->drives_size();
  if (options.simulation.drive >= drives) {
    Fail(kUsageError, "drive " + std::to_string(options.simulation.drive) + " out of range: world '" +
                          options.world + "' has " + std::to_string(drives) + " drives (0-" +
                          std::to_string(drives - 1) + ")");
  }
  options.simulation.world = *world;

  std::optional<FileSink> files;
  std::optional<LiveSink> live;
  std::vector<SimulationSink*> sinks;
  if (options.out) {
    auto opened = FileSink::Open(*options.out, options.files);
    if (!opened.ok()) Fail(kUsageError, opened.error().message);
    files.emplace(std::move(*opened));
    sinks.push_back(&*files);
  }
  if (options.udp) {
    LiveSinkOptions live_options;
    live_options.sender.destination = *options.udp;
    live_options.speed = options.rate;
    auto opened = LiveSink::Open(live_options);
    if (!opened.ok()) Fail(kUsageError, opened.error().message);
    live.emplace(std::move(*opened));
    sinks.push_back(&*live);
  }

  auto summary = RunSimulation(options.simulation, sinks);
  if (!summary.ok()) Fail(kRunError, summary.error().message);
  std::vector<std::string> written;
  if (files) {
    if (Status png = maps::sim_cli::RenderTruthMapPng(*options.out); !png) Fail(kRunError, png.error().message);
    written = maps::sim_cli::OutputFiles(*options.out);
  }
  const maps::sim_cli::RunReport report{options.world, options.simulation, *summary, options.out,
                                        written, live ? live->sent() : 0,
                                        live ? live->send_errors() : 0};
  std::cout << (options.json ? maps::sim_cli::ReportToJson(report) : maps::sim_cli::ReportToText(report));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CliOptions options = ParseArguments(argc, argv);
  if (options.list) return List(options.json);
  return Simulate(options);
}
