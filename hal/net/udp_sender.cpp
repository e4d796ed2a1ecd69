#include "hal/net/udp_sender.hpp"

#include <sys/socket.h>

#include <cerrno>

namespace flat2d::hal::net {

Result<UdpSender> UdpSender::Open(const UdpSenderOptions& options) {
  SocketFd socket(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!socket.valid()) return MakeError("cannot create a UDP socket: " + ErrnoText(errno));
  if (options.allow_broadcast && !SetIntOption(socket, SOL_SOCKET, SO_BROADCAST, 1)) {
    return MakeError("cannot enable broadcast: " + ErrnoText(errno));
  }
  if (options.bind_address != kIpv4Any || options.bind_port != 0) {
    const Ipv4Endpoint local{options.bind_address, options.bind_port};
    const sockaddr_in address = ToSockaddr(local);
    if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
      return MakeError("cannot bind " + FormatEndpoint(local) + ": " + ErrnoText(errno));
    }
  }
  return UdpSender(std::move(socket), options);
}

Status UdpSender::Send(const UdpDatagram& datagram) {
  Ipv4Endpoint destination = options_.destination;
  if (options_.keep_datagram_port && datagram.destination.port != 0) {
    destination.port = datagram.destination.port;
  }
  return SendTo(destination, datagram.payload);
}

Status UdpSender::SendTo(const Ipv4Endpoint& destination, std::span<const std::uint8_t> payload) {
  const sockaddr_in address = ToSockaddr(destination);
  const ssize_t sent = ::sendto(socket_.get(), payload.data(), payload.size(), 0,
                                reinterpret_cast<const sockaddr*>(&address), sizeof(address));
  if (sent < 0) {
    return MakeError("cannot send " + std::to_string(payload.size()) + " bytes to " +
                     FormatEndpoint(destination) + ": " + ErrnoText(errno));
  }
  return Status::Ok();
}

}  // namespace flat2d::hal::net
