#include "hal/net/socket_fd.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <system_error>

namespace flat2d::hal::net {

SocketFd& SocketFd::operator=(SocketFd&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

SocketFd::~SocketFd() {
  if (fd_ >= 0) ::close(fd_);
}

sockaddr_in ToSockaddr(const Ipv4Endpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  address.sin_addr.s_addr = htonl(endpoint.address);
  return address;
}

Ipv4Endpoint FromSockaddr(const sockaddr_in& address) {
  return Ipv4Endpoint{ntohl(address.sin_addr.s_addr), ntohs(address.sin_port)};
}

std::string ErrnoText(int error_number) {
  return std::system_category().message(error_number);
}

bool SetIntOption(const SocketFd& socket, int level, int name, int value) {
  return ::setsockopt(socket.get(), level, name, &value, sizeof(value)) == 0;
}

Ipv4Endpoint LocalEndpoint(const SocketFd& socket) {
  sockaddr_in address{};
  socklen_t length = sizeof(address);
  if (::getsockname(socket.get(), reinterpret_cast<sockaddr*>(&address), &length) != 0) return {};
  return FromSockaddr(address);
}

}  // namespace flat2d::hal::net
