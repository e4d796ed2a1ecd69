// flat2d: the command-line client of flat2dd (daemon/client/client.hpp).
//   flat2d [--socket PATH | --tcp ADDRESS:PORT] [--json] [--timeout MS] COMMAND
//   pose [--at T_NS] | watch [--rate HZ] [--count N] | status | set-pose X Y THETA
//   [--sigma-m S] [--sigma-rad S] | map-info
// Exit codes: 0 done, 1 the daemon answered with an error or could not be reached, 2 usage.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <google/protobuf/util/json_util.h>

#include "daemon/client/client.hpp"

namespace {

namespace v1 = flat2d::api::v1;

constexpr const char* kUsage =
    "usage: flat2d [--socket PATH | --tcp ADDRESS:PORT] [--json] [--timeout MS] COMMAND\n"
    "commands:\n"
    "  pose [--at T_NS]          the global pose now, or at a Unix time in nanoseconds\n"
    "  watch [--rate HZ] [--count N]  poses as the daemon sends them (default 10 Hz, forever)\n"
    "  status                    state, sensor rates, drops, match timing, memory\n"
    "  set-pose X Y THETA [--sigma-m S] [--sigma-rad S]  the vehicle's global pose (m, m, rad)\n"
    "  map-info                  the prior map the daemon runs on\n"
    "default socket: /run/flat2d/api.sock\n";

int Usage(const char* message) {
  std::fprintf(stderr, "flat2d: %s\n%s", message, kUsage);
  return 2;
}

bool ParseDouble(const char* text, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(value);
}

void PrintJson(const google::protobuf::Message& message) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  std::printf("%s\n", json.c_str());
}

void PrintPose(const v1::PoseReply& pose, bool json) {
  if (json) return PrintJson(pose);
  if (!pose.valid()) {
    std::printf("no fix (%s)\n", v1::LocalizerState_Name(pose.state()).c_str());
    return;
  }
  const auto& p = pose.global_t_vehicle();
  const auto& c = pose.covariance();
  std::printf("%.9f  x %.3f m  y %.3f m  theta %.4f rad  sigma %.3f m %.4f rad  %s  last match %.2f s ago\n",
              static_cast<double>(pose.time_ns()) * 1e-9, p.x(), p.y(), p.theta(),
              c.size() == 9 ? std::sqrt(c[0] + c[4]) : 0.0, c.size() == 9 ? std::sqrt(c[8]) : 0.0,
              v1::LocalizerState_Name(pose.state()).c_str(), pose.since_accepted_match_s());
}

void PrintStatus(const v1::Health& health, bool json) {
  if (json) return PrintJson(health);
  std::printf("state      %s\n", v1::LocalizerState_Name(health.state()).c_str());
  std::printf("lidar      %.0f/s, %llu received, %llu dropped, %llu malformed\n", health.lidar().rate_hz(),
              static_cast<unsigned long long>(health.lidar().received()),
              static_cast<unsigned long long>(health.lidar().dropped()),
              static_cast<unsigned long long>(health.lidar().malformed()));
  std::printf("can        %.0f/s, %llu received, %llu dropped, %llu malformed\n", health.can().rate_hz(),
              static_cast<unsigned long long>(health.can().received()),
              static_cast<unsigned long long>(health.can().dropped()),
              static_cast<unsigned long long>(health.can().malformed()));
  std::printf("matches    %llu accepted, %llu rejected, %llu relocalizations, over %llu revolutions\n",
              static_cast<unsigned long long>(health.matches_accepted()),
              static_cast<unsigned long long>(health.matches_rejected()),
              static_cast<unsigned long long>(health.relocalizations()),
              static_cast<unsigned long long>(health.revolutions()));
  std::printf("timing     match p50 %.1f ms p99 %.1f ms, solve p50 %.2f ms p99 %.2f ms, %u graph nodes\n",
              health.match_ms_p50(), health.match_ms_p99(), health.solve_ms_p50(), health.solve_ms_p99(),
              health.graph_nodes());
  std::printf("service    %u clients, %llu malformed requests, RSS %.1f MB, up %.0f s\n", health.clients(),
              static_cast<unsigned long long>(health.malformed_requests()),
              static_cast<double>(health.rss_bytes()) / 1e6, health.uptime_s());
  const v1::GpioHealth& gpio = health.gpio();
  if (gpio.pose_valid_configured()) {
    std::printf("pose valid %s, %llu switches, %llu write failures\n", gpio.pose_valid_on() ? "on" : "off",
                static_cast<unsigned long long>(gpio.pose_valid_switches()),
                static_cast<unsigned long long>(gpio.pose_valid_write_failures()));
  }
  if (gpio.pps_state() != v1::PPS_NOT_CONFIGURED) {
    std::printf("pps        %s, offset %.1f us, drift %.2f ppm, jitter %.1f us, %llu pulses, %llu missed\n",
                v1::PpsState_Name(gpio.pps_state()).c_str(), gpio.pps_offset_us(), gpio.pps_drift_ppm(),
                gpio.pps_jitter_us(), static_cast<unsigned long long>(gpio.pps_pulses()),
                static_cast<unsigned long long>(gpio.pps_missed()));
  }
  if (!health.last_error().empty()) std::printf("last error %s\n", health.last_error().c_str());
}

void PrintMapInfo(const v1::MapInfo& info, bool json) {
  if (json) return PrintJson(info);
  std::printf("%s: %u tiles, %.3f m cells, %llu bytes, %u viewpoints, x %.1f..%.1f m, y %.1f..%.1f m\n",
              info.path().c_str(), info.tiles(), info.resolution_m(),
              static_cast<unsigned long long>(info.file_bytes()), info.viewpoints(), info.min_x(), info.max_x(),
              info.min_y(), info.max_y());
}

int Fail(const flat2d::Error& error) {
  std::fprintf(stderr, "flat2d: %s\n", error.message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  flat2d::client::ClientOptions options;
  bool json = false;
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--socket" || arg == "--tcp" || arg == "--timeout") && i + 1 == argc) return Usage("missing value");
    if (arg == "--socket") {
      options.endpoint = argv[++i];
    } else if (arg == "--tcp") {
      options.endpoint = std::string("tcp:") + argv[++i];
    } else if (arg == "--timeout") {
      options.timeout_ms = std::atoi(argv[++i]);
      if (options.timeout_ms <= 0) return Usage("--timeout must be a positive number of milliseconds");
    } else if (arg == "--json") {
      json = true;
    } else if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      args.push_back(arg);
    }
  }
  if (args.empty()) return Usage("no command");
  flat2d::client::Client client(options);
  const std::string& command = args[0];
  if (command == "pose") {
    std::optional<long long> at;
    for (std::size_t i = 1; i < args.size(); ++i) {
      if (args[i] == "--at" && i + 1 < args.size()) {
        at = std::atoll(args[++i].c_str());
      } else {
        return Usage(("unknown pose argument " + args[i]).c_str());
      }
    }
    auto pose = at ? client.PoseAt(*at) : client.PoseNow();
    if (!pose.ok()) return Fail(pose.error());
    PrintPose(*pose, json);
    return 0;
  }
  if (command == "watch") {
    double rate = 10.0;
    long long count = -1;
    for (std::size_t i = 1; i < args.size(); ++i) {
      if (args[i] == "--rate" && i + 1 < args.size() && ParseDouble(args[i + 1].c_str(), rate) && rate > 0) {
        ++i;
      } else if (args[i] == "--count" && i + 1 < args.size()) {
        count = std::atoll(args[++i].c_str());
      } else {
        return Usage(("bad watch argument " + args[i]).c_str());
      }
    }
    if (flat2d::Status subscribed = client.Subscribe(rate); !subscribed.ok()) return Fail(subscribed.error());
    for (long long n = 0; count < 0 || n < count; ++n) {
      auto pose = client.NextUpdate();
      if (!pose.ok()) return Fail(pose.error());
      PrintPose(*pose, json);
      std::fflush(stdout);
    }
    return 0;
  }
  if (command == "status") {
    auto status = client.GetStatus();
    if (!status.ok()) return Fail(status.error());
    PrintStatus(*status, json);
    return 0;
  }
  if (command == "map-info") {
    auto info = client.GetMapInfo();
    if (!info.ok()) return Fail(info.error());
    PrintMapInfo(*info, json);
    return 0;
  }
  if (command == "set-pose") {
    double x = 0, y = 0, theta = 0, sigma_m = 0, sigma_rad = 0;
    if (args.size() < 4 || !ParseDouble(args[1].c_str(), x) || !ParseDouble(args[2].c_str(), y) ||
        !ParseDouble(args[3].c_str(), theta)) {
      return Usage("set-pose needs X Y THETA (numbers)");
    }
    for (std::size_t i = 4; i < args.size(); ++i) {
      if (args[i] == "--sigma-m" && i + 1 < args.size() && ParseDouble(args[i + 1].c_str(), sigma_m) && sigma_m > 0) {
        ++i;
      } else if (args[i] == "--sigma-rad" && i + 1 < args.size() && ParseDouble(args[i + 1].c_str(), sigma_rad) &&
                 sigma_rad > 0) {
        ++i;
      } else {
        return Usage(("bad set-pose argument " + args[i]).c_str());
      }
    }
    if (flat2d::Status set = client.SetInitialPose(x, y, theta, sigma_m, sigma_rad); !set.ok()) return Fail(set.error());
    if (json) {
      std::printf("{\"ok\": true}\n");
    } else {
      std::printf("initial pose set\n");
    }
    return 0;
  }
  return Usage(("unknown command " + command).c_str());
}
