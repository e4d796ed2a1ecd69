// An owned socket descriptor and the IPv4 sockaddr conversions the UDP code shares.
//
// UdpReceiver and UdpSender are movable values returned from Open(); the descriptor
// must close exactly once whichever object ends up owning it, and error messages must
// name endpoints the same way. Both live here so that neither class repeats them.
#pragma once

#include <netinet/in.h>

#include <string>
#include <utility>

#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

class SocketFd {
 public:
  SocketFd() = default;
  explicit SocketFd(int fd) : fd_(fd) {}
  SocketFd(SocketFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  SocketFd& operator=(SocketFd&& other) noexcept;
  SocketFd(const SocketFd&) = delete;
  SocketFd& operator=(const SocketFd&) = delete;
  ~SocketFd();

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

sockaddr_in ToSockaddr(const Ipv4Endpoint& endpoint);
Ipv4Endpoint FromSockaddr(const sockaddr_in& address);

// The text for an errno value, e.g. "Address already in use" (thread-safe).
std::string ErrnoText(int error_number);

// setsockopt for an int option; false (errno set) if the kernel refused it.
bool SetIntOption(const SocketFd& socket, int level, int name, int value);

// The address the socket is bound to (after bind; port 0 becomes the real port).
Ipv4Endpoint LocalEndpoint(const SocketFd& socket);

}  // namespace flat2d::hal::net
