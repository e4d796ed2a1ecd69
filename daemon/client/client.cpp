#include "daemon/client/client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include "daemon/api/delimited_frames.hpp"

namespace flat2d::client {

namespace v1 = api::v1;
using Clock = std::chrono::steady_clock;

namespace {

constexpr auto kRetryPause = std::chrono::milliseconds(100);

std::string ErrnoMessage(const std::string& what) { return what + ": " + std::strerror(errno); }

Result<int> Dial(const std::string& endpoint) {
  if (endpoint.rfind("tcp:", 0) == 0) {
    const std::string rest = endpoint.substr(4);
    const std::size_t colon = rest.rfind(':');
    sockaddr_in address{};
    address.sin_family = AF_INET;
    if (colon == std::string::npos || inet_pton(AF_INET, rest.substr(0, colon).c_str(), &address.sin_addr) != 1) {
      return MakeError("bad endpoint " + endpoint + " (tcp:ADDRESS:PORT)");
    }
    const int port = std::atoi(rest.substr(colon + 1).c_str());
    if (port <= 0 || port > 65535) return MakeError("bad port in " + endpoint);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return MakeError(ErrnoMessage("socket"));
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
      const std::string message = ErrnoMessage("connect " + endpoint);
      ::close(fd);
      return MakeError(message);
    }
    return fd;
  }
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (endpoint.size() >= sizeof(address.sun_path)) return MakeError("socket path too long: " + endpoint);
  std::memcpy(address.sun_path, endpoint.c_str(), endpoint.size() + 1);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return MakeError(ErrnoMessage("socket"));
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    const std::string message = ErrnoMessage("connect " + endpoint);
    ::close(fd);
    return MakeError(message);
  }
  return fd;
}

}  // namespace

struct Client::Connection {
  explicit Connection(ClientOptions o) : options(std::move(o)), reader(options.max_message_bytes) {}
  ~Connection() { Disconnect(); }

  void Disconnect() {
    if (fd >= 0) ::close(fd);
    fd = -1;
    reader.Reset();
  }

  // Connects, retrying until reconnect_ms has passed; re-subscribes if a subscription ran.
  Status Ensure() {
    if (fd >= 0) return Status::Ok();
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(options.reconnect_ms);
    Error last{""};
    while (true) {
      Result<int> dialed = Dial(options.endpoint);
      if (dialed.ok()) {
        fd = *dialed;
        if (ever_connected) ++reconnects;
        ever_connected = true;
        if (subscribed_hz > 0.0) return SendSubscribe();
        return Status::Ok();
      }
      last = dialed.error();
      if (Clock::now() + kRetryPause > deadline) return last;
      std::this_thread::sleep_for(kRetryPause);
    }
  }

  Status Send(const v1::Request& request) {
    std::vector<std::uint8_t> bytes(request.ByteSizeLong() + wire::kMaxVarint32Bytes);
    const auto used = wire::AppendDelimited(request, options.max_message_bytes, bytes, 0);
    if (!used) return MakeError("request too large");
    std::size_t sent = 0;
    while (sent < *used) {
      const ssize_t n = ::send(fd, bytes.data() + sent, *used - sent, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return MakeError(ErrnoMessage("send"));
      sent += static_cast<std::size_t>(n);
    }
    return Status::Ok();
  }

  // The next whole response within the timeout.
  Result<v1::Response> Receive(int timeout_ms) {
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (true) {
      const wire::FrameStatus status = reader.Next();
      if (status == wire::FrameStatus::kFrame) {
        v1::Response response;
        const auto frame = reader.frame();
        if (!response.ParseFromArray(frame.data(), static_cast<int>(frame.size()))) {
          return MakeError("the daemon sent a response that does not parse");
        }
        return response;
      }
      if (status != wire::FrameStatus::kNeedMore) return MakeError("the daemon sent a bad frame");
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) return MakeError("no response within " + std::to_string(timeout_ms) + " ms");
      pollfd wait{fd, POLLIN, 0};
      if (::poll(&wait, 1, static_cast<int>(left)) <= 0) continue;
      const std::span<std::uint8_t> space = reader.WritableSpace();
      const ssize_t n = ::recv(fd, space.data(), space.size(), 0);
      if (n == 0) return MakeError("the daemon closed the connection");
      if (n < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        return MakeError(ErrnoMessage("recv"));
      }
      reader.Commit(static_cast<std::size_t>(n));
    }
  }

  Status SendSubscribe() {
    v1::Request request;
    request.set_id(subscription_id = ++next_id);
    request.mutable_subscribe()->set_rate_hz(subscribed_hz);
    return Send(request);
  }

  ClientOptions options;
  wire::FrameReader reader;
  int fd = -1;
  bool ever_connected = false;
  std::uint64_t reconnects = 0;
  std::uint64_t next_id = 0;
  double subscribed_hz = 0.0;
  std::uint64_t subscription_id = 0;
};

Client::Client(ClientOptions options) : connection_(std::make_unique<Connection>(std::move(options))) {}
Client::~Client() = default;
Client::Client(Client&&) noexcept = default;
Client& Client::operator=(Client&&) noexcept = default;

std::uint64_t Client::reconnects() const { return connection_->reconnects; }

Result<v1::Response> Client::Call(v1::Request request) {
  Connection& c = *connection_;
  request.set_id(++c.next_id);
  // Retried on a new connection until reconnect_ms after the first failure: a restarting
  // daemon may even accept a connection into the backlog of a listener that is going away.
  std::optional<Clock::time_point> give_up;
  std::string reason;
  while (!give_up || Clock::now() < *give_up) {
    if (Status up = c.Ensure(); !up.ok()) return up.error();
    if (Status sent = c.Send(request); sent.ok()) {
      while (true) {
        Result<v1::Response> response = c.Receive(c.options.timeout_ms);
        if (!response.ok()) {
          reason = response.error().message;
          break;
        }
        if (response->id() == request.id()) return response;
        // A subscription update that arrived meanwhile: skipped, the next is newer anyway.
      }
    } else {
      reason = sent.error().message;
    }
    c.Disconnect();
    if (!give_up) give_up = Clock::now() + std::chrono::milliseconds(c.options.reconnect_ms);
  }
  return MakeError("no response from " + c.options.endpoint + ": " + reason);
}

namespace {

Error ResponseError(const v1::Response& response) {
  if (response.has_error()) {
    return MakeError(v1::Error::Code_Name(response.error().code()) + ": " + response.error().message());
  }
  return MakeError("unexpected response kind");
}

// The reply of one kind a request expects (`has`, `get`), or the daemon's error.
template <typename Reply>
Result<Reply> Expect(Result<v1::Response> response, bool (v1::Response::*has)() const,
                     const Reply& (v1::Response::*get)() const) {
  if (!response.ok()) return response.error();
  if (!((*response).*has)()) return ResponseError(*response);
  return ((*response).*get)();
}

}  // namespace

Result<v1::PoseReply> Client::PoseNow() {
  v1::Request request;
  request.mutable_pose_now();
  return Expect(Call(std::move(request)), &v1::Response::has_pose, &v1::Response::pose);
}

Result<v1::PoseReply> Client::PoseAt(std::int64_t time_ns) {
  v1::Request request;
  request.mutable_pose_at()->set_time_ns(time_ns);
  return Expect(Call(std::move(request)), &v1::Response::has_pose, &v1::Response::pose);
}

Result<v1::Health> Client::GetStatus() {
  v1::Request request;
  request.mutable_status();
  return Expect(Call(std::move(request)), &v1::Response::has_status, &v1::Response::status);
}

Result<v1::MapInfo> Client::GetMapInfo() {
  v1::Request request;
  request.mutable_map_info();
  return Expect(Call(std::move(request)), &v1::Response::has_map_info, &v1::Response::map_info);
}

Status Client::SetInitialPose(double x, double y, double theta, double sigma_m, double sigma_rad) {
  v1::Request request;
  v1::SetInitialPoseRequest& set = *request.mutable_set_initial_pose();
  set.mutable_global_t_vehicle()->set_x(x);
  set.mutable_global_t_vehicle()->set_y(y);
  set.mutable_global_t_vehicle()->set_theta(theta);
  set.set_sigma_m(sigma_m);
  set.set_sigma_rad(sigma_rad);
  auto acked = Expect(Call(std::move(request)), &v1::Response::has_ack, &v1::Response::ack);
  if (!acked.ok()) return acked.error();
  return Status::Ok();
}

Status Client::Subscribe(double rate_hz) {
  Connection& c = *connection_;
  c.subscribed_hz = rate_hz;
  if (c.fd < 0) return c.Ensure();  // connecting subscribes
  return c.SendSubscribe();
}

Result<v1::PoseReply> Client::NextUpdate() {
  Connection& c = *connection_;
  // Three update periods, at least a call's timeout: a silent daemon is a gone daemon.
  const int wait_ms = std::max(c.options.timeout_ms, c.subscribed_hz > 0.0 ? static_cast<int>(3000.0 / c.subscribed_hz) : 0);
  std::string reason;
  std::optional<Clock::time_point> give_up;
  while (!give_up || Clock::now() < *give_up) {
    if (Status up = c.Ensure(); !up.ok()) return up.error();
    while (true) {
      Result<v1::Response> response = c.Receive(wait_ms);
      if (!response.ok()) {
        reason = response.error().message;
        break;
      }
      if (response->id() == c.subscription_id && response->has_pose()) return response->pose();
      if (response->has_error()) return ResponseError(*response);
    }
    c.Disconnect();  // reconnects and re-subscribes on the next round
    if (!give_up) give_up = Clock::now() + std::chrono::milliseconds(c.options.reconnect_ms);
  }
  return MakeError("the subscription to " + c.options.endpoint + " ended: " + reason);
}

}  // namespace flat2d::client
