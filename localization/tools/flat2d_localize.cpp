// flat2d-localize: the daemon's localization pipeline offline on a recorded drive (issue 9
// item 5). Writes the global poses at odometry rate (TUM) and the state timeline, one row per
// revolution; --json prints a summary (states, matches, CPU per revolution).
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read, is invalid or cannot
// be written.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/localizer/localizer_config.hpp"
#include "localization/tools/localize_run.hpp"
#include "localization/tools/shipped_config.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-localize";

constexpr const char* kUsage = R"(usage:
  flat2d-localize --map MAP --pcap P --can LOG --dbc DBC --odometry CONFIG --out est.tum
                  (--initial-pose X,Y,YAW | --initial-from TRACK.tum) [options]

Replays a recorded drive (Velodyne capture and candump log, merged by timestamp) through
the daemon's localization pipeline against a prior map (flat2d-map build): structure grid
per revolution, tracking scan match against the map, sliding-window graph with odometry,
LOCALIZED / DEGRADED / LOST states and global relocalization. Writes the global pose at
every odometry sample once there is a fix (TUM, map frame) and the state timeline.
  --map MAP               prior map file
  --pcap P                Velodyne capture (pcap or pcapng)
  --can LOG --dbc DBC     candump log and the vehicle's DBC
  --odometry CONFIG       odometry configuration (packaging/config/odometry/)
  --config C              LocalizerConfig text file (default: built-in defaults; see
                          packaging/config/localizer/localizer.textproto)
  --grid-config G         StructureGridOptions (default: the shipped structure_grid.textproto)
  --out est.tum           estimated global poses
  --states FILE           state timeline, CSV, one row per revolution (default: est.states.csv)
  --odometry-out FILE     dead reckoning alone from the same initial pose (TUM, map
                          frame): the open-loop odometry to compare with
  --initial-pose X,Y,YAW  initial global pose (metres, radians) at the first odometry sample
  --initial-from T.tum    ... read from a track (GNSS, the simulator's truth) at that time
  --initial-offset DX,DY,DYAW  added to the initial pose (a deliberately wrong start)
  --initial-sigma M,RAD   its standard deviations (default 0.2,0.02); wider than the
                          tracking window starts with a global relocalization
  --realtime              replay at the recorded rate instead of as fast as possible
  --json                  print a summary as one JSON object
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::optional<std::string> map, pcap, can, dbc, odometry, config, grid_config, out, states, odometry_out;
  std::optional<std::string> initial_from;
  localization::LocalizeRunOptions run;
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
    else if (arg == "--config") a.config = value();
    else if (arg == "--grid-config") a.grid_config = value();
    else if (arg == "--out") a.out = value();
    else if (arg == "--states") a.states = value();
    else if (arg == "--odometry-out") a.odometry_out = value();
    else if (arg == "--initial-from") a.initial_from = value();
    else if (arg == "--initial-pose") {
      const auto v = list(3);
      a.run.initial.pose = localization::Se2(Eigen::Vector2d(v[0], v[1]), v[2]);
    } else if (arg == "--initial-offset") {
      const auto v = list(3);
      a.run.initial.offset = Eigen::Vector3d(v[0], v[1], v[2]);
    } else if (arg == "--initial-sigma") {
      const auto v = list(2);
      if (!(v[0] > 0.0 && v[1] > 0.0)) Fail(1, "--initial-sigma must be positive");
      a.run.initial.sigma_m = v[0];
      a.run.initial.sigma_rad = v[1];
    } else if (arg == "--realtime") a.run.realtime = true;
    else if (arg == "--json") a.json = true;
    else Fail(1, "unknown option " + std::string(arg) + " (see --help)");
  }
  if (!a.map || !a.pcap || !a.can || !a.dbc || !a.odometry || !a.out) {
    Fail(1, "needs --map, --pcap, --can, --dbc, --odometry and --out (see --help)");
  }
  if (a.run.initial.pose.has_value() == a.initial_from.has_value()) {
    Fail(1, "give exactly one of --initial-pose and --initial-from");
  }
  if (!a.states) a.states = std::string(std::filesystem::path(*a.out).replace_extension(".states.csv"));
  return a;
}

bool WriteStates(const localization::LocalizeRunResult& result, const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return false;
  std::fprintf(file, "time_s,state,relocalizing,match,score,accepted,points,match_ms,solve_ms\n");
  for (const localization::RevolutionRecord& r : result.revolutions) {
    const localization::RevolutionReport& x = r.report;
    std::fprintf(file, "%.6f,%s,%d,%s,%.4f,%d,%zu,%.3f,%.3f\n", r.time_s,
                 std::string(localization::LocalizerStateName(x.state)).c_str(), x.relocalizing ? 1 : 0,
                 std::string(localization::MatchStatusName(x.match)).c_str(), x.score, x.match_accepted ? 1 : 0,
                 x.points, 1e3 * x.match_s, 1e3 * x.solve_s);
  }
  return std::fclose(file) == 0;
}

void PrintSummary(const localization::LocalizeRunResult& result) {
  std::map<std::string, int> states;
  std::vector<double> match_ms, solve_ms, total_ms;
  std::optional<double> localized_after;
  int used = 0;
  for (const localization::RevolutionRecord& r : result.revolutions) {
    if (!r.report.used) continue;
    ++used;
    ++states[std::string(localization::LocalizerStateName(r.report.state))];
    if (!localized_after && r.report.state == localization::LocalizerState::kLocalized) {
      localized_after = r.time_s - result.first_fix_s;
    }
    match_ms.push_back(1e3 * r.report.match_s);
    solve_ms.push_back(1e3 * r.report.solve_s);
    total_ms.push_back(1e3 * (r.report.match_s + r.report.solve_s));
  }
  const localization::LocalizerStats& s = result.stats;
  std::printf("{\"revolutions\": %zu, \"revolutions_used\": %d, \"poses\": %zu", result.revolutions.size(), used,
              result.estimate.size());
  std::printf(", \"matches_accepted\": %llu, \"matches_rejected\": %llu, \"relocalizations\": %llu, \"relocalized\": %llu"
              ", \"relocalizations_refuted\": %llu",
              static_cast<unsigned long long>(s.matches_accepted), static_cast<unsigned long long>(s.matches_rejected),
              static_cast<unsigned long long>(s.relocalizations), static_cast<unsigned long long>(s.relocalized),
              static_cast<unsigned long long>(s.relocalizations_refuted));
  std::printf(", \"map_window_moves\": %llu, \"map_errors\": %llu, \"grids_without_odometry\": %llu",
              static_cast<unsigned long long>(s.map_window_moves), static_cast<unsigned long long>(s.map_errors),
              static_cast<unsigned long long>(s.grids_without_odometry));
  std::printf(", \"map_prefetches\": %llu, \"map_prefetches_taken\": %llu, \"map_prefetch_waits\": %llu"
              ", \"map_prefetch_ms_mean\": %.3f",
              static_cast<unsigned long long>(s.map_prefetches), static_cast<unsigned long long>(s.map_prefetches_taken),
              static_cast<unsigned long long>(s.map_prefetch_waits),
              s.map_prefetches > 0 ? 1e3 * s.map_prefetch_cpu_s / static_cast<double>(s.map_prefetches) : 0.0);
  std::printf(", \"first_localized_after_s\": %s", localized_after ? std::to_string(*localized_after).c_str() : "null");
  std::printf(", \"states\": {");
  bool first = true;
  for (const auto& [name, count] : states) {
    std::printf("%s\"%s\": %d", first ? "" : ", ", name.c_str(), count);
    first = false;
  }
  const auto match = localization::evaluation::PercentilesOf(std::move(match_ms));
  const auto solve = localization::evaluation::PercentilesOf(std::move(solve_ms));
  const auto total = localization::evaluation::PercentilesOf(std::move(total_ms));
  std::printf("}, \"match_ms_p50\": %.3f, \"match_ms_p99\": %.3f, \"solve_ms_p50\": %.3f, \"solve_ms_p99\": %.3f",
              match.p50, match.p99, solve.p50, solve.p99);
  std::printf(", \"cpu_ms_p50\": %.3f, \"cpu_ms_p99\": %.3f}\n", total.p50, total.p99);
}

}  // namespace

int main(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  localization::LocalizeRunOptions& run = a.run;
  run.map = *a.map;
  run.capture = *a.pcap;
  run.can_log = *a.can;
  run.dbc = *a.dbc;
  run.odometry_config = *a.odometry;
  if (a.config) {
    auto options = localization::LoadLocalizerOptions(*a.config);
    if (!options.ok()) Fail(2, options.error().message);
    run.localizer = *options;
  }
  auto grid = maps::LoadStructureGridOptions(a.grid_config.value_or(localization::ShippedGridConfig()));
  if (!grid.ok()) Fail(2, grid.error().message);
  run.grid = *grid;
  if (a.initial_from) {
    auto track = localization::evaluation::ReadTrajectory(*a.initial_from);
    if (!track.ok()) Fail(2, track.error().message);
    run.initial.track = std::move(*track);
  }
  auto result = localization::RunLocalization(run);
  if (!result.ok()) Fail(2, result.error().message);
  if (Status written = localization::evaluation::WriteTrajectory(result->estimate, *a.out); !written.ok()) {
    Fail(2, written.error().message);
  }
  if (!WriteStates(*result, *a.states)) Fail(2, "cannot write " + *a.states);
  if (a.odometry_out) {
    if (Status written = localization::evaluation::WriteTrajectory(result->odometry, *a.odometry_out); !written.ok()) {
      Fail(2, written.error().message);
    }
  }
  if (a.json) PrintSummary(*result);
  return 0;
}
