// Where replayed or simulated datagrams go: a UDP socket in production, a recorder
// in tests. One virtual Send keeps Replay independent of sockets.
#pragma once

#include "hal/common/error.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

class DatagramSink {
 public:
  virtual ~DatagramSink() = default;
  virtual Status Send(const UdpDatagram& datagram) = 0;

 protected:
  DatagramSink() = default;
  DatagramSink(const DatagramSink&) = default;
  DatagramSink(DatagramSink&&) = default;
  DatagramSink& operator=(const DatagramSink&) = default;
  DatagramSink& operator=(DatagramSink&&) = default;
};

}  // namespace flat2d::hal::net
