#include "daemon/service/api_server.hpp"

#include "hal/net/ipv4.hpp"

#include <arpa/inet.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

namespace flat2d::daemon {

namespace v1 = api::v1;
using hal::net::ErrnoText;
using hal::net::SocketFd;

namespace {

constexpr std::size_t kFramesPerWakeup = 64;  // then the next client's turn (epoll is level-triggered)
constexpr int kMaxEvents = 64;
constexpr int kIdleTimeoutMs = 100;           // the heartbeat's pace when nothing happens
// epoll tags: the wake eventfd; a listener (bit 63, its index); a client (its slot in the low
// 32 bits, the slot's connection generation above, so an event queued for a connection that
// was closed earlier in the same batch cannot act on the next connection in that slot).
constexpr std::uint64_t kWakeTag = ~std::uint64_t{0};
constexpr std::uint64_t kListenerTag = std::uint64_t{1} << 63;
constexpr std::uint64_t kSlotMask = 0xFFFFFFFFu;

std::uint64_t ClientTag(std::size_t slot, std::uint32_t generation) {
  return (static_cast<std::uint64_t>(generation & 0x7FFFFFFFu) << 32) | slot;
}

TimeNs MonotonicNs() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<TimeNs>(now.tv_sec) * kNsPerSecond + now.tv_nsec;
}

Error SystemError(const std::string& what) { return MakeError(what + ": " + ErrnoText(errno)); }

}  // namespace

struct ApiServer::Client {
  explicit Client(const ApiServerOptions& options)
      : reader(options.max_message_bytes), out(2 * (options.max_message_bytes + wire::kMaxVarint32Bytes)) {}
  SocketFd fd;
  wire::FrameReader reader;
  std::vector<std::uint8_t> out;
  std::size_t out_used = 0;
  std::size_t out_sent = 0;
  bool write_interest = false;
  std::uint32_t generation = 0;  // connections this slot has held
  std::uint64_t subscription_id = 0;
  TimeNs period_ns = 0;  // 0: not subscribed
  TimeNs next_update_ns = 0;
};

Result<SocketFd> ListenUnix(const std::string& path, unsigned mode) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(address.sun_path)) {
    return MakeError("unix socket path must be 1.." + std::to_string(sizeof(address.sun_path) - 1) + " bytes: " + path);
  }
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  SocketFd socket(::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!socket.valid()) return SystemError("socket(AF_UNIX)");
  struct stat existing{};
  if (::lstat(path.c_str(), &existing) == 0 && S_ISSOCK(existing.st_mode)) ::unlink(path.c_str());
  if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    return SystemError("bind " + path);
  }
  if (::chmod(path.c_str(), mode) != 0) return SystemError("chmod " + path);
  if (::listen(socket.get(), SOMAXCONN) != 0) return SystemError("listen " + path);
  return socket;
}

Result<SocketFd> ListenTcp(std::uint32_t address, std::uint16_t port) {
  SocketFd socket(::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!socket.valid()) return SystemError("socket(AF_INET)");
  hal::net::SetIntOption(socket, SOL_SOCKET, SO_REUSEADDR, 1);
  const sockaddr_in bound = hal::net::ToSockaddr({address, port});
  if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&bound), sizeof(bound)) != 0) {
    return SystemError("bind tcp " + hal::net::FormatEndpoint({address, port}));
  }
  if (::listen(socket.get(), SOMAXCONN) != 0) return SystemError("listen tcp");
  return socket;
}

Result<std::unique_ptr<ApiServer>> ApiServer::Create(const ApiServerOptions& options, std::vector<SocketFd> listeners,
                                                     ApiHandler& handler) {
  if (options.max_clients == 0 || options.max_message_bytes == 0) return MakeError("api: no clients or no message size");
  std::unique_ptr<ApiServer> server(new ApiServer(options, std::move(listeners), handler));
  if (!server->epoll_.valid()) return SystemError("epoll_create1");
  if (!server->wake_.valid()) return SystemError("eventfd");
  epoll_event event{};
  event.events = EPOLLIN;
  event.data.u64 = kWakeTag;
  if (epoll_ctl(server->epoll_.get(), EPOLL_CTL_ADD, server->wake_.get(), &event) != 0) return SystemError("epoll_ctl");
  for (std::size_t i = 0; i < server->listeners_.size(); ++i) {
    event.data.u64 = kListenerTag | i;
    if (epoll_ctl(server->epoll_.get(), EPOLL_CTL_ADD, server->listeners_[i].get(), &event) != 0) {
      return SystemError("epoll_ctl listener");
    }
  }
  return server;
}

ApiServer::ApiServer(const ApiServerOptions& options, std::vector<SocketFd> listeners, ApiHandler& handler)
    : options_(options),
      listeners_(std::move(listeners)),
      handler_(handler),
      epoll_(epoll_create1(EPOLL_CLOEXEC)),
      wake_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  clients_.reserve(options.max_clients);
  for (std::size_t i = 0; i < options.max_clients; ++i) clients_.push_back(std::make_unique<Client>(options));
}

ApiServer::~ApiServer() = default;

void ApiServer::Stop() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_.get(), &one, sizeof(one));
}

void ApiServer::Run(std::stop_token stop) {
  std::stop_callback on_stop(stop, [this] { Stop(); });
  epoll_event events[kMaxEvents];
  bool stopping = false;
  while (!stopping && !stop.stop_requested()) {
    heartbeat_.fetch_add(1, std::memory_order_relaxed);
    const int ready = epoll_wait(epoll_.get(), events, kMaxEvents, NextTimeoutMs(MonotonicNs()));
    for (int i = 0; i < ready; ++i) {
      const std::uint64_t tag = events[i].data.u64;
      if (tag == kWakeTag) {
        stopping = true;
      } else if ((tag & kListenerTag) != 0) {
        AcceptAll(listeners_[tag & kSlotMask].get());
      } else {
        const std::size_t slot = tag & kSlotMask;
        Client& client = *clients_[slot];
        if (!client.fd.valid() || tag != ClientTag(slot, client.generation)) continue;
        if ((events[i].events & (EPOLLERR | EPOLLHUP)) != 0 && (events[i].events & EPOLLIN) == 0) {
          Close(slot);
          continue;
        }
        if ((events[i].events & EPOLLOUT) != 0 && !Flush(client)) {
          Close(slot);
          continue;
        }
        if ((events[i].events & EPOLLIN) != 0) OnReadable(slot);
        if (client.fd.valid()) UpdateWriteInterest(slot);
      }
    }
    ServeSubscriptions(MonotonicNs());
  }
  for (std::size_t slot = 0; slot < clients_.size(); ++slot) {
    if (clients_[slot]->fd.valid()) Close(slot);
  }
}

void ApiServer::AcceptAll(int listener) {
  while (true) {
    SocketFd accepted(::accept4(listener, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!accepted.valid()) return;  // EAGAIN, or a connection that went away meanwhile
    const auto free_slot = std::find_if(clients_.begin(), clients_.end(), [](const auto& c) { return !c->fd.valid(); });
    if (free_slot == clients_.end()) {
      stats_.refused.fetch_add(1, std::memory_order_relaxed);
      continue;  // closed by SocketFd
    }
    const auto slot = static_cast<std::size_t>(free_slot - clients_.begin());
    hal::net::SetIntOption(accepted, SOL_SOCKET, SO_SNDBUF, options_.socket_send_buffer_bytes);
    Client& client = **free_slot;
    epoll_event event{};
    event.events = EPOLLIN;
    event.data.u64 = ClientTag(slot, client.generation + 1);
    if (epoll_ctl(epoll_.get(), EPOLL_CTL_ADD, accepted.get(), &event) != 0) continue;
    ++client.generation;
    client.fd = std::move(accepted);
    client.reader.Reset();
    client.out_used = client.out_sent = 0;
    client.write_interest = false;
    client.period_ns = 0;
    stats_.accepted.fetch_add(1, std::memory_order_relaxed);
    stats_.clients.fetch_add(1, std::memory_order_relaxed);
  }
}

void ApiServer::OnReadable(std::size_t slot) {
  Client& client = *clients_[slot];
  for (std::size_t round = 0; round < kFramesPerWakeup; ++round) {
    const std::span<std::uint8_t> space = client.reader.WritableSpace();
    const ssize_t received = ::recv(client.fd.get(), space.data(), space.size(), 0);
    if (received == 0 || (received < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      Close(slot);
      return;
    }
    if (received < 0) return;
    client.reader.Commit(static_cast<std::size_t>(received));
    if (!ServeFrames(client)) {
      Flush(client);  // best effort: the error reply, if it fits
      Close(slot);
      return;
    }
    if (static_cast<std::size_t>(received) < space.size()) return;  // drained the socket
  }
}

bool ApiServer::ServeFrames(Client& client) {
  while (true) {
    const wire::FrameStatus status = client.reader.Next();
    if (status == wire::FrameStatus::kNeedMore) return true;
    stats_.requests.fetch_add(1, std::memory_order_relaxed);
    response_.Clear();
    if (status != wire::FrameStatus::kFrame) {
      stats_.malformed_requests.fetch_add(1, std::memory_order_relaxed);
      SetError(response_, v1::Error::MALFORMED,
               status == wire::FrameStatus::kTooLarge
                   ? "request longer than " + std::to_string(options_.max_message_bytes) + " bytes; closing"
                   : "bad length prefix; closing");
      Reply(client, response_);
      return false;
    }
    const std::span<const std::uint8_t> frame = client.reader.frame();
    request_.Clear();
    if (!request_.ParseFromArray(frame.data(), static_cast<int>(frame.size())) ||
        request_.kind_case() == v1::Request::KIND_NOT_SET) {
      stats_.malformed_requests.fetch_add(1, std::memory_order_relaxed);
      SetError(response_, v1::Error::MALFORMED, "the request did not parse or names no kind");
    } else if (request_.has_subscribe()) {
      response_.set_id(request_.id());
      const double rate_hz = request_.subscribe().rate_hz();
      if (!std::isfinite(rate_hz)) {
        SetError(response_, v1::Error::INVALID_ARGUMENT, "rate_hz must be finite");
      } else {
        const double clamped = std::min(rate_hz, options_.max_subscribe_hz);
        client.period_ns = clamped > 0.0 ? static_cast<TimeNs>(1e9 / clamped) : 0;
        client.subscription_id = request_.id();
        client.next_update_ns = MonotonicNs();
        response_.mutable_ack();
      }
    } else {
      handler_.Handle(request_, response_);
    }
    if (!Reply(client, response_)) {
      stats_.slow_disconnects.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
  }
}

bool ApiServer::Reply(Client& client, const v1::Response& response) {
  if (client.out_sent == client.out_used) client.out_sent = client.out_used = 0;
  const auto used = wire::AppendDelimited(response, options_.max_message_bytes, client.out, client.out_used);
  if (!used) return false;
  client.out_used = *used;
  return Flush(client);
}

bool ApiServer::Flush(Client& client) {
  while (client.out_sent < client.out_used) {
    const ssize_t sent = ::send(client.fd.get(), client.out.data() + client.out_sent, client.out_used - client.out_sent,
                                MSG_NOSIGNAL | MSG_DONTWAIT);
    if (sent < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    client.out_sent += static_cast<std::size_t>(sent);
  }
  client.out_sent = client.out_used = 0;
  return true;
}

void ApiServer::UpdateWriteInterest(std::size_t slot) {
  Client& client = *clients_[slot];
  const bool pending = client.out_sent < client.out_used;
  if (pending == client.write_interest) return;
  epoll_event event{};
  event.events = EPOLLIN | (pending ? EPOLLOUT : 0u);
  event.data.u64 = ClientTag(slot, client.generation);
  if (epoll_ctl(epoll_.get(), EPOLL_CTL_MOD, client.fd.get(), &event) == 0) client.write_interest = pending;
}

void ApiServer::ServeSubscriptions(TimeNs now_ns) {
  for (std::size_t slot = 0; slot < clients_.size(); ++slot) {
    Client& client = *clients_[slot];
    if (!client.fd.valid() || client.period_ns == 0 || now_ns < client.next_update_ns) continue;
    client.next_update_ns = std::max(client.next_update_ns + client.period_ns, now_ns);
    if (client.out_sent < client.out_used) {
      stats_.updates_skipped.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    response_.Clear();
    response_.set_id(client.subscription_id);
    handler_.FillPoseNow(*response_.mutable_pose());
    if (!Reply(client, response_)) {
      Close(slot);
      continue;
    }
    stats_.updates_sent.fetch_add(1, std::memory_order_relaxed);
    UpdateWriteInterest(slot);
  }
}

int ApiServer::NextTimeoutMs(TimeNs now_ns) const {
  TimeNs next_ns = now_ns + kIdleTimeoutMs * kNsPerMs;
  for (const auto& client : clients_) {
    if (client->fd.valid() && client->period_ns > 0) next_ns = std::min(next_ns, client->next_update_ns);
  }
  return static_cast<int>(std::max<TimeNs>(0, (next_ns - now_ns + kNsPerMs - 1) / kNsPerMs));
}

void ApiServer::Close(std::size_t slot) {
  Client& client = *clients_[slot];
  epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, client.fd.get(), nullptr);
  client.fd = SocketFd();
  client.period_ns = 0;
  client.reader.Reset();
  client.out_used = client.out_sent = 0;
  stats_.clients.fetch_sub(1, std::memory_order_relaxed);
}

}  // namespace flat2d::daemon
