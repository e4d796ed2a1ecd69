// The flat2dd client library (installed with a CMake package config: find_package(flat2d)
// then target_link_libraries(app flat2d::client)).
//
// A blocking client over the API socket (daemon/api/flat2d_api.proto, length-delimited):
// each call sends one Request and waits, up to timeout_ms, for the Response with its id.
// When the daemon restarts, the next call (or NextUpdate of a subscription) reconnects and
// re-subscribes, retrying until reconnect_ms after the first failure; a call that fails
// after that returns the error. Not thread-safe: one Client per thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "daemon/api/flat2d_api.pb.h"
#include "hal/common/error.hpp"

namespace flat2d::client {

struct ClientOptions {
  // A Unix socket path, or "tcp:ADDRESS:PORT" (e.g. "tcp:127.0.0.1:6370").
  std::string endpoint = "/run/flat2d/api.sock";
  int timeout_ms = 2000;         // per call
  int reconnect_ms = 5000;       // how long a call keeps trying to reach a restarting daemon
  std::size_t max_message_bytes = 1 << 20;
};

class Client {
 public:
  explicit Client(ClientOptions options = {});
  ~Client();
  Client(Client&&) noexcept;
  Client& operator=(Client&&) noexcept;

  // Any request; an Error response is returned as a response, not as an error.
  Result<api::v1::Response> Call(api::v1::Request request);

  Result<api::v1::PoseReply> PoseNow();
  Result<api::v1::PoseReply> PoseAt(std::int64_t time_ns);
  Result<api::v1::Health> GetStatus();
  Result<api::v1::MapInfo> GetMapInfo();
  Status SetInitialPose(double x, double y, double theta, double sigma_m = 0.0, double sigma_rad = 0.0);

  // Starts a subscription; NextUpdate then returns each pose the daemon sends.
  Status Subscribe(double rate_hz);
  Result<api::v1::PoseReply> NextUpdate();

  std::uint64_t reconnects() const;

 private:
  struct Connection;
  std::unique_ptr<Connection> connection_;
};

}  // namespace flat2d::client
