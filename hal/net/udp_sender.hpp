// Sending UDP datagrams to one IPv4 host, for replaying captures and for tests.
//
// Replay feeds the daemon's receiver exactly as a sensor would, so a Velodyne data
// packet goes to port 2368 and a position packet to 8308 on the chosen host. Steps:
// (1) Open creates a blocking socket (a replayer wants back-pressure, not drops),
// optionally binds a source address such as 127.0.0.2 to look like another host, and
// enables broadcast if asked; (2) Send(UdpDatagram) sends the payload to the
// configured address and, by default, the datagram's own destination port.
#pragma once

#include <cstdint>
#include <span>

#include "hal/common/error.hpp"
#include "hal/net/datagram_sink.hpp"
#include "hal/net/ipv4.hpp"
#include "hal/net/socket_fd.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

struct UdpSenderOptions {
  Ipv4Endpoint destination{kIpv4Loopback, 2368};
  // Send(UdpDatagram) keeps each datagram's destination port (2368 data, 8308
  // position); false sends everything to destination.port.
  bool keep_datagram_port = true;
  std::uint32_t bind_address = kIpv4Any;  // source address, e.g. 127.0.0.2
  std::uint16_t bind_port = 0;            // source port; 0: ephemeral
  bool allow_broadcast = false;           // needed for 255.255.255.255 destinations
};

class UdpSender final : public DatagramSink {
 public:
  static Result<UdpSender> Open(const UdpSenderOptions& options = {});

  UdpSender(UdpSender&&) noexcept = default;
  UdpSender& operator=(UdpSender&&) noexcept = default;
  ~UdpSender() override = default;

  Status Send(const UdpDatagram& datagram) override;
  Status SendTo(const Ipv4Endpoint& destination, std::span<const std::uint8_t> payload);
  Status SendPayload(std::span<const std::uint8_t> payload) {
    return SendTo(options_.destination, payload);
  }

  Ipv4Endpoint local_endpoint() const { return LocalEndpoint(socket_); }

 private:
  UdpSender(SocketFd socket, const UdpSenderOptions& options)
      : socket_(std::move(socket)), options_(options) {}

  SocketFd socket_;
  UdpSenderOptions options_;
};

}  // namespace flat2d::hal::net
