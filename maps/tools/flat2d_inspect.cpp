// flat2d-inspect: summarise a Velodyne capture, render a revolution, replay or record.
// Exit status: 0 ok, 1 usage or option error, 2 the capture cannot be read,
// 3 no decodable Velodyne data (e.g. an unsupported model).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/common/angles.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/calibration_yaml.hpp"
#include "hal/velodyne/capture_summary.hpp"
#include "hal/velodyne/capture_summary_json.hpp"
#include "maps/tools/cli_args.hpp"
#include "maps/tools/inspect_record_replay.hpp"
#include "maps/tools/inspect_render.hpp"

namespace {

using namespace flat2d;
using namespace flat2d::hal::velodyne;

constexpr const char* kUsage = R"(usage:
  flat2d-inspect [options] CAPTURE          summarise a capture (pcap, pcapng, raw 1206-byte dump)
  flat2d-inspect replay [options] CAPTURE   send its payloads to UDP with the original timing
  flat2d-inspect record [options] --out F   capture live sensor packets into a pcap file

summary options:
  --json                one JSON object on stdout
  --model NAME          VLP-16 | HDL-32E | VLP-32C (default: identified from the packets)
  --calibration FILE    calibration YAML (velodyne_pointcloud / nebula format)
  --cut-angle DEG       azimuth where revolutions are cut (default 0)
  --data-port P         sensor data port, 0 = any (default 2368)
  --position-port P     sensor position port, 0 = any (default 8308)
  --png FILE            render one revolution top-down to FILE
  --revolution N        which complete revolution to render (default 0)
  --colour height|intensity   (default height)
  --extent M            half-width of the picture in metres (default 50)
  --resolution M        metres per pixel (default 0.1)
)";

struct Options {
  bool json = false;
  std::string capture;
  std::optional<std::string> png;
  hal::velodyne::CaptureSummaryOptions summary;
  std::optional<std::string> calibration;
  maps::TopDownOptions render;
};

constexpr std::string_view kTool = "flat2d-inspect";
constexpr std::int64_t kMaxPort = 65535;

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

double ParseNumber(std::string_view flag, const char* text) {
  return maps::cli::ParseNumber(kTool, flag, text);
}

std::uint16_t ParsePort(std::string_view flag, const char* text) {
  return static_cast<std::uint16_t>(maps::cli::ParseInteger(kTool, flag, text, 0, kMaxPort));
}

Options ParseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--json") {
      options.json = true;
    } else if (arg == "--model") {
      const char* name = value();
      options.summary.stream.model = ParseModelName(name);
      if (!options.summary.stream.model) Fail(1, std::string("unknown model: ") + name);
    } else if (arg == "--calibration") {
      options.calibration = value();
    } else if (arg == "--cut-angle") {
      options.summary.stream.revolution.cut_azimuth_rad = ParseNumber(arg, value()) * kDegToRad;
    } else if (arg == "--data-port") {
      options.summary.stream.data_port = ParsePort(arg, value());
    } else if (arg == "--position-port") {
      options.summary.stream.position_port = ParsePort(arg, value());
    } else if (arg == "--png") {
      options.png = value();
    } else if (arg == "--revolution") {
      options.summary.keep_revolution =
          static_cast<std::size_t>(maps::cli::ParseInteger(kTool, arg, value(), 0, 1'000'000));
    } else if (arg == "--colour" || arg == "--color") {
      const std::string_view by = value();
      if (by != "height" && by != "intensity") Fail(1, "--colour takes height or intensity");
      options.render.colour_by = by == "height" ? maps::TopDownColour::kHeight : maps::TopDownColour::kIntensity;
    } else if (arg == "--extent") {
      options.render.half_extent_m = ParseNumber(arg, value());
    } else if (arg == "--resolution") {
      options.render.metres_per_pixel = ParseNumber(arg, value());
    } else if (!arg.empty() && arg[0] == '-') {
      Fail(1, "unknown option " + std::string(arg) + "\n" + kUsage);
    } else if (options.capture.empty()) {
      options.capture = arg;
    } else {
      Fail(1, "more than one capture given");
    }
  }
  if (options.capture.empty()) Fail(1, std::string("no capture given\n") + kUsage);
  return options;
}

void PrintText(const CaptureSummary& summary) {
  const VelodyneStreamStats& s = summary.stream;
  std::cout << "product:          " << summary.product << "\n";
  if (summary.identification) {
    const Identification& id = *summary.identification;
    std::cout << "return mode:      " << ReturnModeName(id.return_mode) << "\n"
              << "model decided by: " << id.decided_by << "\n";
    for (const std::string& d : id.disagreements) std::cout << "disagreement:     " << d << "\n";
  }
  if (summary.model_error) std::cout << "error:            " << summary.model_error->message << "\n";
  std::cout << "data packets:     " << s.data_packets << "\n"
            << "position packets: " << s.position_packets << "\n"
            << "revolutions:      " << s.revolutions << " complete, " << s.partial_revolutions << " partial\n"
            << "points:           " << s.points << "\n"
            << "malformed:        " << s.malformed + summary.capture.malformed << "\n"
            << "lost packets:     " << s.lost_packets << " (pauses " << s.pauses << ", out of order "
            << s.out_of_order << ")\n"
            << "time source:      " << TimeSourceName(summary.time_source) << "\n";
  if (summary.capture.file_truncated) std::cout << "capture damaged:  " << summary.capture.file_error << "\n";
}

int Summarize(int argc, char** argv) {
  Options options = ParseOptions(argc, argv);
  if (options.calibration) {
    auto table = LoadCalibrationYaml(*options.calibration, options.summary.stream.model);
    if (!table.ok()) Fail(1, table.error().message);
    options.summary.stream.calibration = *table;
  }
  auto source = hal::net::OpenCapture(options.capture);
  if (!source.ok()) Fail(2, source.error().message);
  const CaptureSummary summary = SummarizeCapture(**source, options.summary);

  if (options.json) {
    std::cout << CaptureSummaryToJson(summary, options.capture) << "\n";
  } else {
    PrintText(summary);
  }
  if (summary.model_error) {
    std::cerr << "flat2d-inspect: " << summary.model_error->message << "\n";
    return 3;
  }
  if (options.png) {
    if (summary.kept_revolution.empty()) Fail(3, "no revolution to render");
    auto drawn = maps::RenderRevolutionPng(summary.kept_revolution, options.render, *options.png);
    if (!drawn.ok()) Fail(2, drawn.error().message);
    std::cerr << "flat2d-inspect: wrote " << *options.png << " (" << *drawn << " points)\n";
  }
  return summary.stream.data_packets > 0 ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string_view(argv[1]) == "replay") return flat2d::maps::RunReplay(argc - 1, argv + 1);
  if (argc >= 2 && std::string_view(argv[1]) == "record") return flat2d::maps::RunRecord(argc - 1, argv + 1);
  return Summarize(argc, argv);
}
