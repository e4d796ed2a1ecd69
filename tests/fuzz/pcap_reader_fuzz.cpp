// libFuzzer target: arbitrary bytes as a pcap/pcapng image into PcapReader.
//
// The reader faces files from the field (cut recordings, odd link types, damaged
// disks); whatever the bytes, opening and draining must end without a crash, a leak
// or undefined behaviour, and the counters must account for every frame read.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "hal/net/pcap_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using flat2d::hal::net::PcapReader;
  flat2d::Result<PcapReader> reader = PcapReader::OpenMemory(std::span(data, size));
  if (!reader.ok()) return 0;
  std::uint64_t datagrams = 0;
  std::uint64_t payload_checksum = 0;
  while (const std::optional<flat2d::hal::net::UdpDatagram> datagram = reader->Next()) {
    ++datagrams;
    // Touch every payload byte so that ASan sees any view past the record buffer.
    for (const std::uint8_t byte : datagram->payload) payload_checksum += byte;
  }
  const flat2d::hal::net::CaptureStats& stats = reader->stats();
  const std::uint64_t accounted = stats.udp_datagrams + stats.non_udp + stats.fragments +
                                  stats.malformed + stats.truncated_frames;
  if (datagrams != stats.udp_datagrams || accounted != stats.frames) std::abort();
  // Also what keeps the payload loop from being optimised away.
  if (stats.frames == 0 && payload_checksum != 0) std::abort();
  return 0;
}
