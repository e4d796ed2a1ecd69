// Asks a flat2dd for its pose; with no daemon at the socket it says so and exits 1.
#include <cstdio>

#include "daemon/client/client.hpp"

int main(int argc, char** argv) {
  flat2d::client::ClientOptions options;
  if (argc > 1) options.endpoint = argv[1];
  options.reconnect_ms = 0;
  flat2d::client::Client client(options);
  auto pose = client.PoseNow();
  if (!pose.ok()) {
    std::fprintf(stderr, "pose_printer: %s\n", pose.error().message.c_str());
    return 1;
  }
  std::printf("%s\n", flat2d::api::v1::LocalizerState_Name(pose->state()).c_str());
  return 0;
}
