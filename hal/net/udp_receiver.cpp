#include "hal/net/udp_receiver.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <vector>

namespace flat2d::hal::net {
namespace {

// recvmmsg's kernel limit on messages per call (UIO_MAXIOV).
constexpr std::size_t kMaxBatchSize = 1024;

// Room for the three control messages we enable: the receive time, the drop counter
// and the packet info (header destination address).
constexpr std::size_t kControlBytes = CMSG_SPACE(sizeof(timespec)) +
                                      CMSG_SPACE(sizeof(std::uint32_t)) +
                                      CMSG_SPACE(sizeof(in_pktinfo));

struct ControlBlock {
  alignas(cmsghdr) std::array<unsigned char, kControlBytes> bytes;
};

}  // namespace

// One slot per datagram of a batch, all sized at Open: batch_size x
// max_datagram_bytes payload bytes plus the headers recvmmsg fills in.
struct ReceiveBuffers {
  ReceiveBuffers(std::size_t batch_size, std::size_t max_datagram_bytes)
      : payloads(batch_size * max_datagram_bytes),
        headers(batch_size),
        iovecs(batch_size),
        sources(batch_size),
        controls(batch_size),
        datagrams(batch_size) {}

  std::vector<std::uint8_t> payloads;
  std::vector<mmsghdr> headers;
  std::vector<iovec> iovecs;
  std::vector<sockaddr_in> sources;
  std::vector<ControlBlock> controls;
  std::vector<UdpDatagram> datagrams;
};

namespace {

struct ControlInfo {
  std::optional<TimeNs> receive_time_ns;
  std::optional<std::uint32_t> kernel_drops;
  std::optional<std::uint32_t> destination_address;
};

ControlInfo ReadControlMessages(msghdr& header) {
  ControlInfo info;
  for (cmsghdr* message = CMSG_FIRSTHDR(&header); message != nullptr;
       message = CMSG_NXTHDR(&header, message)) {
    const unsigned char* data = CMSG_DATA(message);
    if (message->cmsg_level == SOL_SOCKET && message->cmsg_type == SCM_TIMESTAMPNS) {
      timespec time{};
      std::memcpy(&time, data, sizeof(time));  // cmsg data need not be aligned for it
      info.receive_time_ns = time.tv_sec * kNsPerSecond + time.tv_nsec;
    } else if (message->cmsg_level == SOL_SOCKET && message->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t drops = 0;
      std::memcpy(&drops, data, sizeof(drops));
      info.kernel_drops = drops;
    } else if (message->cmsg_level == IPPROTO_IP && message->cmsg_type == IP_PKTINFO) {
      in_pktinfo packet_info{};
      std::memcpy(&packet_info, data, sizeof(packet_info));
      info.destination_address = ntohl(packet_info.ipi_addr.s_addr);
    }
  }
  return info;
}

TimeNs RealtimeNow() {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return now.tv_sec * kNsPerSecond + now.tv_nsec;
}

Status ValidateOptions(const UdpReceiverOptions& options) {
  if (options.batch_size == 0 || options.batch_size > kMaxBatchSize) {
    return MakeError("UDP receiver batch size " + std::to_string(options.batch_size) +
                     " is not 1..1024");
  }
  if (options.max_datagram_bytes == 0 || options.max_datagram_bytes > kMaxUdpPayloadBytes) {
    return MakeError("UDP receiver max datagram size " +
                     std::to_string(options.max_datagram_bytes) + " is not 1..65507 bytes");
  }
  if (options.multicast_group && !IsIpv4Multicast(*options.multicast_group)) {
    return MakeError("UDP receiver multicast group " + FormatIpv4(*options.multicast_group) +
                     " is not in 224.0.0.0/4");
  }
  return Status::Ok();
}

// The request is a wish: without CAP_NET_ADMIN the kernel caps SO_RCVBUF at
// net.core.rmem_max, so try the privileged option first and fall back.
void RequestReceiveBuffer(const SocketFd& socket, int bytes) {
  if (bytes <= 0) return;
  if (!SetIntOption(socket, SOL_SOCKET, SO_RCVBUFFORCE, bytes)) {
    (void)SetIntOption(socket, SOL_SOCKET, SO_RCVBUF, bytes);
  }
}

Status BindAndJoin(const SocketFd& socket, const UdpReceiverOptions& options) {
  const Ipv4Endpoint bind_endpoint{options.bind_address, options.port};
  const sockaddr_in bind_address = ToSockaddr(bind_endpoint);
  if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&bind_address),
             sizeof(bind_address)) != 0) {
    return MakeError("cannot bind " + FormatEndpoint(bind_endpoint) + ": " + ErrnoText(errno));
  }
  if (!options.multicast_group) return Status::Ok();
  ip_mreq request{};
  request.imr_multiaddr.s_addr = htonl(*options.multicast_group);
  request.imr_interface.s_addr = htonl(options.multicast_interface);
  if (::setsockopt(socket.get(), IPPROTO_IP, IP_ADD_MEMBERSHIP, &request, sizeof(request)) != 0) {
    return MakeError("cannot join multicast group " + FormatIpv4(*options.multicast_group) +
                     " on interface " + FormatIpv4(options.multicast_interface) + ": " +
                     ErrnoText(errno));
  }
  return Status::Ok();
}

}  // namespace

UdpReceiver::UdpReceiver(SocketFd socket, const UdpReceiverOptions& options)
    : socket_(std::move(socket)),
      options_(options),
      buffers_(std::make_unique<ReceiveBuffers>(options.batch_size, options.max_datagram_bytes)),
      local_endpoint_(LocalEndpoint(socket_)) {
  int bytes = 0;
  socklen_t length = sizeof(bytes);
  if (::getsockopt(socket_.get(), SOL_SOCKET, SO_RCVBUF, &bytes, &length) == 0) {
    receive_buffer_bytes_ = bytes;
  }
}

UdpReceiver::UdpReceiver(UdpReceiver&&) noexcept = default;
UdpReceiver& UdpReceiver::operator=(UdpReceiver&&) noexcept = default;
UdpReceiver::~UdpReceiver() = default;

Result<UdpReceiver> UdpReceiver::Open(const UdpReceiverOptions& options) {
  if (Status valid = ValidateOptions(options); !valid) return valid.error();
  SocketFd socket(::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!socket.valid()) return MakeError("cannot create a UDP socket: " + ErrnoText(errno));
  if (options.reuse_address && !SetIntOption(socket, SOL_SOCKET, SO_REUSEADDR, 1)) {
    return MakeError("cannot set SO_REUSEADDR: " + ErrnoText(errno));
  }
  RequestReceiveBuffer(socket, options.receive_buffer_bytes);
  // Best effort: without these the datagrams are still delivered, stamped from
  // CLOCK_REALTIME, without drop counts or header destinations (stats tell).
  (void)SetIntOption(socket, SOL_SOCKET, SO_TIMESTAMPNS, 1);
  (void)SetIntOption(socket, SOL_SOCKET, SO_RXQ_OVFL, 1);
  (void)SetIntOption(socket, IPPROTO_IP, IP_PKTINFO, 1);
  if (Status bound = BindAndJoin(socket, options); !bound) return bound.error();
  return UdpReceiver(std::move(socket), options);
}

std::span<const UdpDatagram> UdpReceiver::ReceiveBatch(int timeout_ms) {
  pollfd poll_request{socket_.get(), POLLIN, 0};
  const int ready = ::poll(&poll_request, 1, timeout_ms);
  if (ready <= 0) {
    if (ready < 0 && errno != EINTR) ++stats_.errors;
    return {};
  }
  ReceiveBuffers& buffers = *buffers_;
  // The kernel overwrites lengths and flags, so every slot is re-armed per call.
  for (std::size_t i = 0; i < options_.batch_size; ++i) {
    buffers.iovecs[i] = {buffers.payloads.data() + i * options_.max_datagram_bytes,
                         options_.max_datagram_bytes};
    msghdr& header = buffers.headers[i].msg_hdr;
    header = {};
    header.msg_name = &buffers.sources[i];
    header.msg_namelen = sizeof(sockaddr_in);
    header.msg_iov = &buffers.iovecs[i];
    header.msg_iovlen = 1;
    header.msg_control = buffers.controls[i].bytes.data();
    header.msg_controllen = kControlBytes;
  }
  const int count = ::recvmmsg(socket_.get(), buffers.headers.data(),
                               static_cast<unsigned>(options_.batch_size), MSG_DONTWAIT, nullptr);
  if (count < 0) {
    if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) ++stats_.errors;
    return {};
  }
  std::size_t accepted = 0;
  TimeNs fallback_time_ns = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
    if (std::optional<UdpDatagram> datagram = Accept(i, fallback_time_ns)) {
      buffers.datagrams[accepted++] = *datagram;
    }
  }
  return {buffers.datagrams.data(), accepted};
}

std::optional<UdpDatagram> UdpReceiver::Accept(std::size_t index, TimeNs& fallback_time_ns) {
  ReceiveBuffers& buffers = *buffers_;
  msghdr& header = buffers.headers[index].msg_hdr;
  const ControlInfo control = ReadControlMessages(header);
  if (control.kernel_drops) stats_.kernel_drops = *control.kernel_drops;
  if ((header.msg_flags & MSG_TRUNC) != 0) {
    ++stats_.truncated;
    return std::nullopt;
  }
  const Ipv4Endpoint source = FromSockaddr(buffers.sources[index]);
  if (options_.source_filter && source.address != *options_.source_filter) {
    ++stats_.filtered_by_source;
    return std::nullopt;
  }
  TimeNs receive_time_ns = 0;
  if (control.receive_time_ns) {
    receive_time_ns = *control.receive_time_ns;
  } else {
    ++stats_.without_kernel_time;
    if (fallback_time_ns == 0) fallback_time_ns = RealtimeNow();  // once per batch
    receive_time_ns = fallback_time_ns;
  }
  const Ipv4Endpoint destination{control.destination_address.value_or(local_endpoint_.address),
                                 local_endpoint_.port};
  ++stats_.received;
  const std::span<const std::uint8_t> payload(
      buffers.payloads.data() + index * options_.max_datagram_bytes,
      buffers.headers[index].msg_len);
  return UdpDatagram{receive_time_ns, source, destination, payload};
}

}  // namespace flat2d::hal::net
