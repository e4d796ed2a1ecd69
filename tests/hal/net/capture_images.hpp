// Hand-built capture bytes for the hal/net tests: IPv4/UDP packets, link-layer
// frames around them, and whole pcap / pcapng file images.
//
// The reader is tested against bytes written here from the format specifications
// (tcpdump.org LINKTYPE pages, pcapng draft), not against our own writer, so that a
// shared misunderstanding cannot make both sides agree. Everything is little-endian
// unless a function says otherwise.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net::testing {

using Bytes = std::vector<std::uint8_t>;

struct Ipv4Shape {
  std::uint8_t protocol = 17;
  std::uint16_t flags_and_fragment_offset = 0x4000;  // DF
  std::uint8_t ihl_words = 5;
  int udp_length_delta = 0;           // added to the correct UDP length
  int ipv4_total_length_delta = 0;    // added to the correct IPv4 total length
};

// An IPv4 packet carrying one UDP datagram (valid header checksum).
Bytes Ipv4Udp(const Ipv4Endpoint& source, const Ipv4Endpoint& destination, const Bytes& payload,
              const Ipv4Shape& shape = {});

// Ethernet II; each VLAN tag is an (EtherType 0x8100/0x88a8, TCI) pair, outermost first.
struct VlanTag {
  std::uint16_t ether_type = 0x8100;
  std::uint16_t tci = 0;
};
Bytes EthernetFrame(const Bytes& packet, std::uint16_t ether_type = 0x0800,
                    const std::vector<VlanTag>& tags = {});
Bytes SllFrame(const Bytes& packet, std::uint16_t protocol = 0x0800);
Bytes Sll2Frame(const Bytes& packet, std::uint16_t protocol = 0x0800);
Bytes BsdLoopbackFrame(const Bytes& packet, std::uint32_t family, bool big_endian);

struct Record {
  std::uint32_t seconds = 0;
  std::uint32_t fraction = 0;  // microseconds or nanoseconds, as the file says
  Bytes frame;
  std::uint32_t original_length = 0;  // 0: frame.size()
};

// pcap (libpcap format), little-endian, microsecond or nanosecond magic.
Bytes PcapImage(std::uint32_t link_type, const std::vector<Record>& records,
                bool nanosecond = true);

// pcapng with one SHB, one IDB (if_tsresol 9 when nanosecond) and one EPB per record.
Bytes PcapngImage(std::uint32_t link_type, const std::vector<Record>& records,
                  bool nanosecond = true);

Bytes PayloadOf(const UdpDatagram& datagram);
Bytes CountingPayload(std::size_t size, std::uint8_t first = 0);

// A path under the gtest temp dir, unique to this process.
std::filesystem::path TempPath(const std::string& name);

// Writes bytes to TempPath(name) and returns the path.
std::filesystem::path WriteTempFile(const std::string& name, const Bytes& bytes);

}  // namespace flat2d::hal::net::testing
