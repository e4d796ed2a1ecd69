// The API server (DESIGN.md "daemon/"): one epoll loop that owns the listening sockets
// (Unix stream, optional TCP on loopback, or the ones systemd passed) and a fixed table of
// client slots, each with a receive buffer of one largest request and a send buffer, all
// sized at Create.
//
// Per readable client: read what fits, cut length-delimited frames (delimited_frames.hpp),
// parse each as a Request and answer it through the ApiHandler; a frame that does not parse
// gets an Error and the connection stays, a frame longer than max_message_bytes closes it.
// Sends are non-blocking: a reply that does not fit the client's send buffer means the
// client is not reading, and it is disconnected. Subscriptions are served from the loop's
// timer: an update goes out only when the client's send buffer has drained, so a slow
// subscriber gets the newest pose when it is ready and never a growing queue. A full client
// table refuses new connections (closed at once, counted). No client can affect another.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <stop_token>
#include <string>
#include <vector>

#include "daemon/api/delimited_frames.hpp"
#include "daemon/api/flat2d_api.pb.h"
#include "daemon/service/api_handler.hpp"
#include "hal/common/error.hpp"
#include "hal/net/socket_fd.hpp"

namespace flat2d::daemon {

struct ApiServerOptions {
  std::size_t max_clients = 64;
  std::size_t max_message_bytes = 4096;
  double max_subscribe_hz = 100.0;
  // SO_SNDBUF of each client socket: the kernel's queue towards a slow client is bounded
  // too, so "no growing queue" holds end to end (Linux doubles the value for bookkeeping).
  int socket_send_buffer_bytes = 8192;
};

struct ApiServerStats {
  std::atomic<std::uint64_t> accepted{0};
  std::atomic<std::uint64_t> refused{0};              // client table full
  std::atomic<std::uint64_t> requests{0};
  std::atomic<std::uint64_t> malformed_requests{0};   // did not parse, or too long
  std::atomic<std::uint64_t> slow_disconnects{0};     // a reply did not fit: not reading
  std::atomic<std::uint64_t> updates_sent{0};
  std::atomic<std::uint64_t> updates_skipped{0};      // the subscriber had not drained yet
  std::atomic<std::uint32_t> clients{0};
};

// A listening Unix stream socket at `path` (a stale socket file is replaced) with `mode`.
Result<hal::net::SocketFd> ListenUnix(const std::string& path, unsigned mode);
// A listening TCP socket (address and port in host order).
Result<hal::net::SocketFd> ListenTcp(std::uint32_t address, std::uint16_t port);

class ApiServer {
 public:
  static Result<std::unique_ptr<ApiServer>> Create(const ApiServerOptions& options,
                                                   std::vector<hal::net::SocketFd> listeners, ApiHandler& handler);
  ~ApiServer();

  void Run(std::stop_token stop);  // the API thread's body; returns after Stop or a stop request
  void Stop();                     // any thread

  std::uint64_t heartbeat() const { return heartbeat_.load(std::memory_order_relaxed); }
  const ApiServerStats& stats() const { return stats_; }

 private:
  struct Client;
  ApiServer(const ApiServerOptions& options, std::vector<hal::net::SocketFd> listeners, ApiHandler& handler);

  void AcceptAll(int listener);
  void OnReadable(std::size_t slot);
  bool ServeFrames(Client& client);  // false: close it
  bool Reply(Client& client, const api::v1::Response& response);
  bool Flush(Client& client);        // false: the connection failed
  void UpdateWriteInterest(std::size_t slot);
  void ServeSubscriptions(TimeNs now_ns);
  int NextTimeoutMs(TimeNs now_ns) const;
  void Close(std::size_t slot);

  ApiServerOptions options_;
  std::vector<hal::net::SocketFd> listeners_;
  ApiHandler& handler_;
  hal::net::SocketFd epoll_;
  hal::net::SocketFd wake_;  // eventfd
  std::vector<std::unique_ptr<Client>> clients_;
  api::v1::Request request_;    // reused for every request
  api::v1::Response response_;  // ... and reply
  ApiServerStats stats_;
  std::atomic<std::uint64_t> heartbeat_{0};
};

}  // namespace flat2d::daemon
