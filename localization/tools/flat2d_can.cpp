// flat2d-can: decode a CAN log with a DBC, or dead-reckon it with an odometry configuration.
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read or is invalid.
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "localization/tools/can_log_summary.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-can";
constexpr const char* kUsage = R"(usage:
  flat2d-can decode --dbc DBC LOG [--csv] [--signals A,B,...] [--json]
      --csv        one row per decoded signal value: time,message,signal,value
      --signals    only these signals (SIGNAL or MESSAGE.SIGNAL); default all of the DBC
      --json       a summary: frames, frames per id, malformed lines, checksum failures, duration
  flat2d-can odom --dbc DBC --config ODOM LOG --tum OUT [--json]
      --config     odometry configuration (packaging/config/odometry/*.textproto)
      --tum        write the dead-reckoned trajectory, TUM format "t x y z qx qy qz qw"
      --json       a summary as for decode, plus samples, distance, final pose
LOG is a candump -l log: "(seconds.micros) iface ID#HEX".
)";

struct Options {
  std::string command;
  std::string dbc, log, config, tum;
  std::vector<std::string> signals;
  bool csv = false;
  bool json = false;
};

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

std::vector<std::string> SplitCommas(std::string_view text) {
  std::vector<std::string> parts;
  std::stringstream stream{std::string(text)};
  for (std::string part; std::getline(stream, part, ',');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

Options Parse(int argc, char** argv) {
  if (argc < 2) Fail(1, std::string("no command\n") + kUsage);
  Options options;
  options.command = argv[1];
  if (options.command == "--help" || options.command == "-h") {
    std::cout << kUsage;
    std::exit(0);
  }
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--dbc") options.dbc = value();
    else if (arg == "--config") options.config = value();
    else if (arg == "--tum") options.tum = value();
    else if (arg == "--signals") options.signals = SplitCommas(value());
    else if (arg == "--csv") options.csv = true;
    else if (arg == "--json") options.json = true;
    else if (arg == "--help" || arg == "-h") std::cout << kUsage, std::exit(0);
    else if (!arg.empty() && arg[0] == '-') Fail(1, "unknown option " + std::string(arg) + "\n" + kUsage);
    else if (options.log.empty()) options.log = arg;
    else Fail(1, "more than one log given");
  }
  if (options.dbc.empty()) Fail(1, "--dbc is required");
  if (options.log.empty()) Fail(1, "no log given");
  return options;
}

void PrintText(const localization::CanLogSummary& s, bool odometry) {
  std::cout << "frames:            " << s.log.frames << " (" << s.frames_per_id.size() << " ids)\n"
            << "duration:          " << static_cast<double>(s.last_ns - s.first_ns) * 1e-9 << " s\n"
            << "malformed lines:   " << s.log.malformed << "\n"
            << "decoded frames:    " << s.decoder.decoded << "\n"
            << "checksum failures: " << s.decoder.checksum_failures << " of " << s.decoder.checksum_checked << "\n";
  if (odometry) {
    std::cout << "samples:           " << s.samples << "\n"
              << "distance:          " << s.distance_m << " m\n";
  }
}

int Decode(const Options& options) {
  if (options.csv && options.json) Fail(1, "--csv and --json both write to stdout: choose one");
  auto summary = localization::DecodeCanLog(options.dbc, options.log, options.signals,
                                            options.csv ? &std::cout : nullptr);
  if (!summary.ok()) Fail(2, summary.error().message);
  if (options.json) std::cout << localization::CanLogSummaryToJson(*summary, false) << "\n";
  if (!options.csv && !options.json) PrintText(*summary, false);
  return 0;
}

int Odometry(const Options& options) {
  if (options.config.empty()) Fail(1, "odom needs --config ODOM");
  if (options.tum.empty()) Fail(1, "odom needs --tum OUT");
  std::ofstream tum(options.tum);
  if (!tum) Fail(2, options.tum + ": cannot write");
  auto summary = localization::DeadReckonCanLog(options.dbc, options.config, options.log, tum);
  if (!summary.ok()) Fail(2, summary.error().message);
  tum.close();
  if (!tum) Fail(2, options.tum + ": write failed");
  if (options.json) {
    std::cout << localization::CanLogSummaryToJson(*summary, true) << "\n";
  } else {
    PrintText(*summary, true);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = Parse(argc, argv);
  if (options.command == "decode") return Decode(options);
  if (options.command == "odom") return Odometry(options);
  Fail(1, "unknown command '" + options.command + "'\n" + kUsage);
}
