// Link-layer frame -> IPv4 -> UDP decoding for captured frames.
//
// A capture file stores whole frames of one link type; this header finds the UDP
// datagram inside one frame. Steps: (1) strip the link header (Ethernet with any
// number of 802.1Q/802.1ad VLAN tags up to a bound, Linux cooked SLL/SLL2, BSD
// loopback, or nothing for raw IP) to reach an EtherType or address family;
// (2) check the IPv4 header (version, IHL, total length); (3) reject fragments,
// because a lone fragment is not a whole datagram; (4) check that the UDP length fits
// the IPv4 payload. One inconsistency is tolerated: an IPv4 total length beyond the
// end of a complete frame, if the UDP length fits the bytes that are there. Early
// VLP-16 firmware sends its 554-byte position packets with the data packets' total
// length (1234), and dropping them would lose the GPS/PPS data; such datagrams are
// flagged so that readers can count them. Every rejection is a verdict, never a
// crash: the caller counts it. Checksums are not verified, because captures taken on
// the sending host carry offloaded (unfilled) checksums on perfectly good packets.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

// The link layers we can read UDP from. Values are ours, not DLT numbers, because
// DLT numbers differ between platforms (DLT_RAW is 12 or 14, DLT_LOOP 12 or 108).
enum class LinkLayer {
  kEthernet,      // DLT_EN10MB, with optional VLAN tags
  kLinuxSll,      // DLT_LINUX_SLL, 16-byte cooked header
  kLinuxSll2,     // DLT_LINUX_SLL2, 20-byte cooked header
  kRawIp,         // DLT_RAW (12/14), LINKTYPE_RAW 101: IPv4 or IPv6, no link header
  kRawIpv4,       // LINKTYPE_IPV4 228: IPv4 only
  kBsdLoopback,   // DLT_NULL / DLT_LOOP: 4-byte address family
};

// The LinkLayer for a libpcap DLT value, or nullopt if we cannot read UDP from it.
std::optional<LinkLayer> LinkLayerFromDlt(int dlt);

// Human-readable DLT name for error messages, e.g. "IEEE802_11 (105)".
std::string DescribeDlt(int dlt);

enum class FrameVerdict {
  kUdp,        // datagram filled in
  kNotUdp,     // well-formed, but not IPv4/UDP (ARP, IPv6, TCP, ...)
  kFragment,   // IPv4/UDP fragment: not a whole datagram
  kMalformed,  // headers inconsistent with each other or with the captured bytes
};

struct ParsedFrame {
  FrameVerdict verdict = FrameVerdict::kMalformed;
  Ipv4Endpoint source;
  Ipv4Endpoint destination;
  std::span<const std::uint8_t> payload;  // view into the frame
  bool ipv4_length_overrun = false;  // kUdp despite an IPv4 total length past the frame
};

// Decodes one captured frame. `frame` must be the complete frame (not cut by snaplen).
ParsedFrame ParseFrame(LinkLayer link, std::span<const std::uint8_t> frame);

}  // namespace flat2d::hal::net
