// Fuzzes the Velodyne front end: the input is cut into datagrams (a 2-byte length, a
// 1-byte port selector, then the payload) and pushed through VelodyneStream, which
// exercises model identification, the packet decoder, position packets, sequence
// checks and revolution assembly on arbitrary bytes.
#include <cstddef>
#include <cstdint>
#include <optional>

#include "hal/net/udp_datagram.hpp"
#include "hal/velodyne/velodyne_stream.hpp"

namespace {

using namespace flat2d::hal;

// Lengths near the real sizes are likelier than uniform ones, so most inputs become
// packets the decoder accepts as well-formed and the deeper stages get exercised.
std::size_t PickLength(std::uint16_t code, std::size_t remaining) {
  std::size_t length = code & 0x7FF;
  if (code & 0x8000) length = velodyne::kDataPacketSize;
  else if (code & 0x4000) length = velodyne::kPositionPacketSize;
  return length < remaining ? length : remaining;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  velodyne::VelodyneStreamOptions options;
  if (size > 0 && data[0] < 3) options.model = static_cast<velodyne::Model>(data[0]);
  std::size_t revolutions = 0;
  velodyne::VelodyneStream stream(options, [&](const velodyne::Revolution& r) {
    revolutions += r.fans.size();
  });
  std::size_t offset = 1;
  while (offset + 3 <= size) {
    const std::uint16_t code = static_cast<std::uint16_t>(data[offset] | (data[offset + 1] << 8));
    const std::uint8_t port_selector = data[offset + 2];
    offset += 3;
    const std::size_t length = PickLength(code, size - offset);
    net::UdpDatagram datagram;
    datagram.receive_time_ns = static_cast<flat2d::TimeNs>(offset) * 1000;
    datagram.destination.port = port_selector % 3 == 0   ? velodyne::kDefaultDataPort
                                : port_selector % 3 == 1 ? velodyne::kDefaultPositionPort
                                                         : port_selector;
    datagram.payload = std::span(data + offset, length);
    stream.Push(datagram);
    offset += length;
  }
  stream.Finish();
  return 0;
}
