// One UDP datagram as it reached us: from a live socket or from a capture file.
//
// The payload is a view into the source's own buffer and stays valid until the source
// is advanced; copy it if you keep it.
#pragma once

#include <cstdint>
#include <span>

#include "hal/common/time.hpp"

namespace flat2d::hal::net {

struct Ipv4Endpoint {
  std::uint32_t address = 0;  // host byte order, e.g. 0xC0A801C9 for 192.168.1.201
  std::uint16_t port = 0;
};

struct UdpDatagram {
  TimeNs receive_time_ns = 0;  // capture timestamp or kernel receive time, Unix epoch
  Ipv4Endpoint source;
  Ipv4Endpoint destination;
  std::span<const std::uint8_t> payload;
};

}  // namespace flat2d::hal::net
