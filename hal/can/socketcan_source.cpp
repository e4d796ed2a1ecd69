#include "hal/can/socketcan_source.hpp"

#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>

namespace flat2d::hal::can {
namespace {

// Frames Next may skip (error frames, bad sizes) before it returns, so that an error
// storm cannot keep the caller's loop in one call.
constexpr int kMaxSkippedPerCall = 64;

struct ControlInfo {
  std::optional<TimeNs> receive_time_ns;
  std::optional<std::uint32_t> kernel_drops;
};

ControlInfo ReadControlMessages(msghdr& header) {
  ControlInfo info;
  for (cmsghdr* message = CMSG_FIRSTHDR(&header); message != nullptr;
       message = CMSG_NXTHDR(&header, message)) {
    if (message->cmsg_level != SOL_SOCKET) continue;
    if (message->cmsg_type == SCM_TIMESTAMPNS) {
      timespec time{};
      std::memcpy(&time, CMSG_DATA(message), sizeof(time));  // cmsg data may be unaligned
      info.receive_time_ns = time.tv_sec * kNsPerSecond + time.tv_nsec;
    } else if (message->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t drops = 0;
      std::memcpy(&drops, CMSG_DATA(message), sizeof(drops));
      info.kernel_drops = drops;
    }
  }
  return info;
}

TimeNs RealtimeNow() {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return now.tv_sec * kNsPerSecond + now.tv_nsec;
}

Status ValidateOptions(const SocketCanOptions& options) {
  if (options.interface_name.empty() || options.interface_name.size() >= IFNAMSIZ) {
    return MakeError("CAN interface name '" + options.interface_name + "' is not 1.." +
                     std::to_string(IFNAMSIZ - 1) + " characters (IFNAMSIZ)");
  }
  if (options.timeout_ms < -1) {
    return MakeError("CAN receive timeout " + std::to_string(options.timeout_ms) +
                     " ms is not -1 (forever), 0 or positive");
  }
  return Status::Ok();
}

Result<net::SocketFd> CreateSocket() {
  net::SocketFd socket(::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW));
  if (socket.valid()) return socket;
  const int error = errno;
  if (error == EAFNOSUPPORT) {
    return MakeError("this kernel has no AF_CAN support (socket: " + net::ErrnoText(error) + ")");
  }
  if (error == EPROTONOSUPPORT) {
    return MakeError("this kernel has no CAN_RAW support, is module can-raw loaded? (socket: " +
                     net::ErrnoText(error) + ")");
  }
  return MakeError("cannot create a CAN_RAW socket: " + net::ErrnoText(error));
}

// Filters and error subscription; a kernel that refuses them would deliver the wrong frames.
Status InstallFilters(const net::SocketFd& socket, const std::vector<can_filter>& filters,
                      const SocketCanOptions& options) {
  const std::string where = " on CAN interface '" + options.interface_name + "': ";
  if (!filters.empty() &&
      ::setsockopt(socket.get(), SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                   static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0) {
    return MakeError("cannot set CAN_RAW_FILTER" + where + net::ErrnoText(errno));
  }
  const can_err_mask_t error_mask = options.error_frames ? CAN_ERR_MASK : 0;
  if (::setsockopt(socket.get(), SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &error_mask,
                   sizeof(error_mask)) != 0) {
    return MakeError("cannot set CAN_RAW_ERR_FILTER" + where + net::ErrnoText(errno));
  }
  return Status::Ok();
}

Status Bind(const net::SocketFd& socket, const std::string& name) {
  const unsigned index = ::if_nametoindex(name.c_str());
  if (index == 0) return MakeError("no CAN interface '" + name + "': " + net::ErrnoText(errno));
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    return MakeError("cannot bind to CAN interface '" + name + "': " + net::ErrnoText(errno));
  }
  return Status::Ok();
}

}  // namespace

SocketCanSource::SocketCanSource(net::SocketFd socket, const SocketCanOptions& options,
                                 bool fd_enabled)
    : socket_(std::move(socket)), timeout_ms_(options.timeout_ms), fd_enabled_(fd_enabled) {
  std::copy_n(options.interface_name.begin(),
              std::min(options.interface_name.size(), interface_.size() - 1), interface_.begin());
}

Result<SocketCanSource> SocketCanSource::Open(const SocketCanOptions& options) {
  // Configuration errors first, so that they read the same on machines without CAN.
  if (Status valid = ValidateOptions(options); !valid) return valid.error();
  const Result<std::vector<can_filter>> filters = BuildCanFilters(options.ids);
  if (!filters) return filters.error();
  Result<net::SocketFd> socket = CreateSocket();
  if (!socket) return socket.error();
  if (Status installed = InstallFilters(*socket, *filters, options); !installed) {
    return installed.error();
  }
  const bool fd_enabled =
      options.fd_frames && net::SetIntOption(*socket, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, 1);
  // Best effort, as for UDP: frames still arrive, stamped later, drops uncounted (stats say).
  (void)net::SetIntOption(*socket, SOL_SOCKET, SO_TIMESTAMPNS, 1);
  (void)net::SetIntOption(*socket, SOL_SOCKET, SO_RXQ_OVFL, 1);
  if (options.receive_buffer_bytes > 0) {
    (void)net::SetIntOption(*socket, SOL_SOCKET, SO_RCVBUF, options.receive_buffer_bytes);
  }
  if (Status bound = Bind(*socket, options.interface_name); !bound) return bound.error();
  return SocketCanSource(std::move(*socket), options, fd_enabled);
}

bool SocketCanSource::Next(CanFrame& frame) {
  bool waited = false;
  for (int skipped = 0; skipped < kMaxSkippedPerCall;) {
    switch (ReceiveOne(frame)) {
      case Received::kFrame: return true;
      case Received::kSkipped: ++skipped; break;
      case Received::kNothing:
        if (waited || !WaitReadable()) return false;
        waited = true;
        break;
    }
  }
  return false;
}

bool SocketCanSource::WaitReadable() {
  pollfd request{socket_.get(), POLLIN, 0};
  const int ready = ::poll(&request, 1, timeout_ms_);
  if (ready < 0 && errno != EINTR) {
    ++stats_.receive_errors;
    stats_.last_errno = errno;
  }
  return ready > 0;
}

SocketCanSource::Received SocketCanSource::ReceiveOne(CanFrame& frame) {
  iovec buffer{&raw_, sizeof(raw_)};
  msghdr header{};
  header.msg_iov = &buffer;
  header.msg_iovlen = 1;
  header.msg_control = control_.data();
  header.msg_controllen = control_.size();
  const ssize_t bytes = ::recvmsg(socket_.get(), &header, MSG_DONTWAIT);
  if (bytes < 0) {
    if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      ++stats_.receive_errors;
      stats_.last_errno = errno;
    }
    return Received::kNothing;
  }
  const ControlInfo control = ReadControlMessages(header);
  if (control.kernel_drops) stats_.kernel_drops = *control.kernel_drops;
  if (!control.receive_time_ns) ++stats_.without_kernel_time;
  const TimeNs time_ns = control.receive_time_ns ? *control.receive_time_ns : RealtimeNow();
  const bool truncated = (header.msg_flags & MSG_TRUNC) != 0;
  const RawFrameKind kind = truncated ? RawFrameKind::kInvalid
                                      : ConvertRawFrame(raw_, static_cast<std::size_t>(bytes),
                                                        time_ns, frame);
  switch (kind) {
    case RawFrameKind::kData:
      frame.interface = interface_;
      ++stats_.frames;
      if (frame.fd) ++stats_.fd_frames;
      return Received::kFrame;
    case RawFrameKind::kError: CountErrorFrame(ClassifyErrorFrame(frame), stats_.errors); break;
    case RawFrameKind::kInvalid: ++stats_.invalid; break;
  }
  return Received::kSkipped;
}

}  // namespace flat2d::hal::can
