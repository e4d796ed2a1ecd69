// flat2dd: the localization service (daemon/service/daemon.hpp). Usage:
//   flat2dd [--config /etc/flat2d/flat2dd.textproto] [--check]
// --check loads and checks the configuration and everything it names, then exits.
#include <cstdio>
#include <cstring>
#include <string>

#include "daemon/config/daemon_config.hpp"
#include "daemon/service/daemon.hpp"

namespace {

constexpr const char* kDefaultConfig = "/etc/flat2d/flat2dd.textproto";
constexpr const char* kUsage =
    "usage: flat2dd [--config FILE] [--check]\n"
    "  --config FILE  configuration in protobuf text format (default /etc/flat2d/flat2dd.textproto)\n"
    "  --check        load and check the configuration, the map and the files it names; then exit\n";

}  // namespace

int main(int argc, char** argv) {
  std::string config = kDefaultConfig;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0 && i + 1 < argc) {
      config = argv[++i];
    } else if (std::strcmp(argv[i], "--check") == 0) {
      check = true;
    } else if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fprintf(stderr, "flat2dd: unknown argument %s\n%s", argv[i], kUsage);
      return 2;
    }
  }
  if (check) {
    auto inputs = flat2d::daemon::LoadDaemonInputs(config);
    if (!inputs.ok()) {
      std::fprintf(stderr, "flat2dd: %s\n", inputs.error().message.c_str());
      return 1;
    }
    std::printf("flat2dd: %s is valid\n", config.c_str());
    return 0;
  }
  auto daemon = flat2d::daemon::Daemon::Start(config);
  if (!daemon.ok()) {
    std::fprintf(stderr, "flat2dd: %s\n", daemon.error().message.c_str());
    return 1;
  }
  return (*daemon)->Run();
}
