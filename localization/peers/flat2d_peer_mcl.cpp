// flat2d-peer-mcl: MRPT's Monte-Carlo localization on a recorded drive, the peer that
// flat2d-localize is compared with (issue 9; mcl_run.hpp says how). Writes the filter's
// mean pose per revolution (TUM, map frame); --json prints the CPU per revolution.
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read, is invalid or cannot
// be written.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/peers/mcl_run.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-peer-mcl";

constexpr const char* kUsage = R"(usage:
  flat2d-peer-mcl --map MAP --pcap P --can LOG --dbc DBC --odometry CONFIG
                  --initial-from TRACK.tum --out est.tum [options]

MRPT's particle-filter localization (CMonteCarloLocalization2D, likelihood field) of a
recorded drive against an occupancy grid made from a prior map (flat2d-map build): the
slammable cells of each revolution's structure grid as a 360-degree range scan, the CAN
odometry since the last revolution as the motion. The comparison peer of flat2d-localize;
writes the particles' mean pose per revolution (TUM, map frame).
  --map MAP               prior map file
  --pcap P                Velodyne capture (pcap or pcapng)
  --can LOG --dbc DBC     candump log and the vehicle's DBC
  --odometry CONFIG       odometry configuration (packaging/config/odometry/)
  --grid-config G         StructureGridOptions (default: the shipped structure_grid.textproto)
  --initial-from T.tum    the start: the track's pose at the first revolution's time
  --initial-offset DX,DY,DYAW  added to it
  --initial-sigma M,RAD   the particles' initial spread (default 0.2,0.02)
  --particles N           particle count (default 1000)
  --resolution M          occupancy grid cell size, metres (default 0.10)
  --rays N                rays of the 360-degree scan (default 5760)
  --ray-decimation N      the likelihood field uses every Nth ray (default 2)
  --hit-sigma M           the likelihood field's range sigma, metres (default 0.35)
  --seed N                random seed (default 1)
  --out est.tum           estimated global poses
  --json                  print a summary as one JSON object
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::optional<std::string> map, pcap, can, dbc, odometry, grid_config, initial_from, out;
  localization::peers::MclRunOptions run;
  bool json = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return std::string(maps::cli::OptionValue(kTool, argc, argv, i)); };
    auto list = [&](std::size_t n) { return maps::cli::ParseNumberList(kTool, arg, value(), n); };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--map") a.map = value();
    else if (arg == "--pcap") a.pcap = value();
    else if (arg == "--can") a.can = value();
    else if (arg == "--dbc") a.dbc = value();
    else if (arg == "--odometry") a.odometry = value();
    else if (arg == "--grid-config") a.grid_config = value();
    else if (arg == "--initial-from") a.initial_from = value();
    else if (arg == "--out") a.out = value();
    else if (arg == "--initial-offset") {
      const auto v = list(3);
      a.run.initial.offset = Eigen::Vector3d(v[0], v[1], v[2]);
    } else if (arg == "--initial-sigma") {
      const auto v = list(2);
      if (!(v[0] > 0.0 && v[1] > 0.0)) Fail(1, "--initial-sigma must be positive");
      a.run.initial.sigma_m = v[0];
      a.run.initial.sigma_rad = v[1];
    } else if (arg == "--particles") {
      a.run.mcl.particles = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value().c_str(), 1, 1'000'000));
    } else if (arg == "--resolution") {
      a.run.mcl.occupancy_resolution_m = maps::cli::ParseNumber(kTool, arg, value().c_str());
      if (!(a.run.mcl.occupancy_resolution_m >= 0.02 && a.run.mcl.occupancy_resolution_m <= 2.0)) {
        Fail(1, "--resolution must be within [0.02, 2] m");
      }
    } else if (arg == "--rays") {
      a.run.scan.rays = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value().c_str(), 36, 36'000));
    } else if (arg == "--ray-decimation") {
      a.run.mcl.ray_decimation = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value().c_str(), 1, 1000));
    } else if (arg == "--hit-sigma") {
      a.run.mcl.hit_sigma_m = static_cast<float>(maps::cli::ParseNumber(kTool, arg, value().c_str()));
      if (!(a.run.mcl.hit_sigma_m > 0.0f && a.run.mcl.hit_sigma_m <= 5.0f)) Fail(1, "--hit-sigma must be in (0, 5] m");
    } else if (arg == "--seed") {
      a.run.mcl.seed = static_cast<unsigned>(maps::cli::ParseInteger(kTool, arg, value().c_str(), 0, 4'294'967'295));
    } else if (arg == "--json") a.json = true;
    else Fail(1, "unknown option " + std::string(arg) + " (see --help)");
  }
  if (!a.map || !a.pcap || !a.can || !a.dbc || !a.odometry || !a.initial_from || !a.out) {
    Fail(1, "needs --map, --pcap, --can, --dbc, --odometry, --initial-from and --out (see --help)");
  }
  return a;
}

void PrintSummary(const Args& a, const localization::peers::MclRunResult& result) {
  const localization::peers::OccupancyStats& o = result.occupancy;
  const auto returns = localization::evaluation::PercentilesOf({result.scan_returns.begin(), result.scan_returns.end()});
  const auto step = localization::evaluation::PercentilesOf(result.step_cpu_ms);
  double total_ms = 0.0;
  for (double ms : result.step_cpu_ms) total_ms += ms;
  std::printf("{\"revolutions\": %llu, \"poses\": %zu, \"particles\": %d, \"resolution_m\": %.3f",
              static_cast<unsigned long long>(result.revolutions), result.estimate.size(), a.run.mcl.particles,
              a.run.mcl.occupancy_resolution_m);
  std::printf(", \"occupancy\": {\"cells\": %zu, \"occupied\": %zu, \"free\": %zu, \"cpu_ms\": %.1f}", o.cells,
              o.occupied, o.free, result.occupancy_cpu_ms);
  std::printf(", \"scan_returns_p50\": %.0f, \"cpu_ms_p50\": %.3f, \"cpu_ms_p99\": %.3f, \"cpu_ms_total\": %.1f}\n",
              returns.p50, step.p50, step.p99, total_ms);
}

}  // namespace

int main(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  localization::peers::MclRunOptions& run = a.run;
  run.map = *a.map;
  run.capture = *a.pcap;
  run.can_log = *a.can;
  run.dbc = *a.dbc;
  run.odometry_config = *a.odometry;
  auto grid = maps::LoadStructureGridOptions(a.grid_config.value_or(localization::ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  run.grid = *grid;
  auto track = localization::evaluation::ReadTrajectory(*a.initial_from);
  if (!track.ok()) Fail(2, track.error().message);
  run.initial.track = std::move(*track);
  auto result = localization::peers::RunMcl(run);
  if (!result.ok()) Fail(2, result.error().message);
  if (Status written = localization::evaluation::WriteTrajectory(result->estimate, *a.out); !written.ok()) {
    Fail(2, written.error().message);
  }
  if (a.json) PrintSummary(a, *result);
  return 0;
}
