#include "hal/net/frame_parser.hpp"

#include <pcap/pcap.h>

#include <algorithm>

#include "hal/net/byte_order.hpp"
#include "hal/net/ipv4.hpp"

namespace flat2d::hal::net {
namespace {

constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
constexpr std::uint16_t kEtherTypeVlan = 0x8100;        // 802.1Q
constexpr std::uint16_t kEtherTypeQinQ = 0x88A8;        // 802.1ad
constexpr std::uint16_t kEtherTypeQinQLegacy = 0x9100;  // pre-standard QinQ
// Real networks stack at most two tags (QinQ); a few more tolerates odd gear while
// bounding the work a hostile frame can cause.
constexpr int kMaxVlanTags = 4;
constexpr std::size_t kEthernetTypeOffset = 12;
constexpr std::size_t kVlanTagBytes = 4;
constexpr std::size_t kSllHeaderBytes = 16;
constexpr std::size_t kSllProtocolOffset = 14;
constexpr std::size_t kSll2HeaderBytes = 20;
constexpr std::size_t kSll2ProtocolOffset = 0;
constexpr std::size_t kLoopbackHeaderBytes = 4;
constexpr std::uint32_t kLoopbackFamilyInet = 2;  // AF_INET on every BSD and Linux

// The address families of IPv6 in DLT_NULL headers (BSD, FreeBSD, Darwin, Linux).
bool IsLoopbackFamilyIpv6(std::uint32_t family) {
  return family == 24 || family == 28 || family == 30 || family == 10;
}

constexpr std::uint8_t kIpProtocolUdp = 17;
constexpr std::uint16_t kIpv4MoreFragmentsFlag = 0x2000;
constexpr std::uint16_t kIpv4FragmentOffsetMask = 0x1FFF;

ParsedFrame Verdict(FrameVerdict verdict) {
  ParsedFrame parsed;
  parsed.verdict = verdict;
  return parsed;
}

ParsedFrame ParseUdp(std::span<const std::uint8_t> ip_payload, ParsedFrame parsed) {
  if (ip_payload.size() < kUdpHeaderBytes) return Verdict(FrameVerdict::kMalformed);
  const std::uint16_t udp_length = LoadBe16(ip_payload, 4);
  // UDP length counts its own header and must fit in the IPv4 payload we have.
  if (udp_length < kUdpHeaderBytes || udp_length > ip_payload.size()) {
    return Verdict(FrameVerdict::kMalformed);
  }
  parsed.source.port = LoadBe16(ip_payload, 0);
  parsed.destination.port = LoadBe16(ip_payload, 2);
  parsed.payload = ip_payload.subspan(kUdpHeaderBytes, udp_length - kUdpHeaderBytes);
  parsed.verdict = FrameVerdict::kUdp;
  return parsed;
}

ParsedFrame ParseIpv4Packet(std::span<const std::uint8_t> packet) {
  if (packet.size() < kIpv4MinHeaderBytes) return Verdict(FrameVerdict::kMalformed);
  if ((packet[0] >> 4) != 4) return Verdict(FrameVerdict::kMalformed);
  const std::size_t header_bytes = std::size_t{packet[0] & 0x0Fu} * 4;
  const std::size_t total_length = LoadBe16(packet, 2);
  if (header_bytes < kIpv4MinHeaderBytes || total_length < header_bytes ||
      header_bytes > packet.size()) {
    return Verdict(FrameVerdict::kMalformed);
  }
  if (packet[9] != kIpProtocolUdp) return Verdict(FrameVerdict::kNotUdp);
  const std::uint16_t flags_and_offset = LoadBe16(packet, 6);
  if ((flags_and_offset & (kIpv4MoreFragmentsFlag | kIpv4FragmentOffsetMask)) != 0) {
    return Verdict(FrameVerdict::kFragment);
  }
  ParsedFrame parsed;
  parsed.source.address = LoadBe32(packet, 12);
  parsed.destination.address = LoadBe32(packet, 16);
  // Frames may carry padding after the IPv4 packet (Ethernet minimum size), so the
  // total length may be shorter than the bytes; longer is the firmware quirk above,
  // and the UDP length check against the real bytes decides.
  parsed.ipv4_length_overrun = total_length > packet.size();
  const std::size_t packet_end = std::min(total_length, packet.size());
  return ParseUdp(packet.subspan(header_bytes, packet_end - header_bytes), parsed);
}

// Walks VLAN tags from `ether_type` (whose payload starts at `payload_offset`) to
// the IPv4 packet, if any. A tag is TCI(2) + the next EtherType(2) in front of the
// payload, the same after an Ethernet header as after a cooked SLL/SLL2 header.
ParsedFrame ParseFromEtherType(std::span<const std::uint8_t> frame, std::uint16_t ether_type,
                               std::size_t payload_offset) {
  for (int tags = 0; tags <= kMaxVlanTags; ++tags) {
    if (ether_type == kEtherTypeIpv4) return ParseIpv4Packet(frame.subspan(payload_offset));
    if (ether_type != kEtherTypeVlan && ether_type != kEtherTypeQinQ &&
        ether_type != kEtherTypeQinQLegacy) {
      return Verdict(FrameVerdict::kNotUdp);
    }
    if (frame.size() < payload_offset + kVlanTagBytes) return Verdict(FrameVerdict::kMalformed);
    ether_type = LoadBe16(frame, payload_offset + 2);
    payload_offset += kVlanTagBytes;
  }
  return Verdict(FrameVerdict::kMalformed);
}

// A link header of `header_bytes` whose EtherType is at `type_offset`.
ParsedFrame ParseLinkHeader(std::span<const std::uint8_t> frame, std::size_t header_bytes,
                            std::size_t type_offset) {
  if (frame.size() < header_bytes) return Verdict(FrameVerdict::kMalformed);
  return ParseFromEtherType(frame, LoadBe16(frame, type_offset), header_bytes);
}

ParsedFrame ParseRawIp(std::span<const std::uint8_t> packet, bool ipv6_allowed) {
  if (packet.empty()) return Verdict(FrameVerdict::kMalformed);
  const int version = packet[0] >> 4;
  if (version == 4) return ParseIpv4Packet(packet);
  if (version == 6 && ipv6_allowed) return Verdict(FrameVerdict::kNotUdp);
  return Verdict(FrameVerdict::kMalformed);
}

ParsedFrame ParseBsdLoopback(std::span<const std::uint8_t> frame) {
  if (frame.size() < kLoopbackHeaderBytes) return Verdict(FrameVerdict::kMalformed);
  // DLT_NULL stores the family in the capturing host's order, DLT_LOOP in network
  // order; AF_INET is 2 everywhere, so accepting both orders is unambiguous.
  const std::uint32_t family_le = LoadLe32(frame, 0);
  const std::uint32_t family_be = LoadBe32(frame, 0);
  if (family_le == kLoopbackFamilyInet || family_be == kLoopbackFamilyInet) {
    return ParseIpv4Packet(frame.subspan(kLoopbackHeaderBytes));
  }
  if (IsLoopbackFamilyIpv6(family_le) || IsLoopbackFamilyIpv6(family_be)) {
    return Verdict(FrameVerdict::kNotUdp);
  }
  return Verdict(FrameVerdict::kMalformed);
}

}  // namespace

std::optional<LinkLayer> LinkLayerFromDlt(int dlt) {
  switch (dlt) {
    case 1: return LinkLayer::kEthernet;
    case 113: return LinkLayer::kLinuxSll;
    case 276: return LinkLayer::kLinuxSll2;
    case 12:   // DLT_RAW everywhere but OpenBSD (where 12 is DLT_LOOP; we run on Linux)
    case 14:   // DLT_RAW on OpenBSD and BSD/OS
    case 101:  // LINKTYPE_RAW, if a libpcap passes the file value through
      return LinkLayer::kRawIp;
    case 228: return LinkLayer::kRawIpv4;
    case 0:    // DLT_NULL
    case 108:  // DLT_LOOP
      return LinkLayer::kBsdLoopback;
    default: return std::nullopt;
  }
}

std::string DescribeDlt(int dlt) {
  const char* name = pcap_datalink_val_to_name(dlt);
  const std::string number = std::to_string(dlt);
  return name != nullptr ? std::string(name) + " (" + number + ")" : number;
}

ParsedFrame ParseFrame(LinkLayer link, std::span<const std::uint8_t> frame) {
  switch (link) {
    case LinkLayer::kEthernet:
      return ParseLinkHeader(frame, kEthernetHeaderBytes, kEthernetTypeOffset);
    case LinkLayer::kLinuxSll:
      return ParseLinkHeader(frame, kSllHeaderBytes, kSllProtocolOffset);
    case LinkLayer::kLinuxSll2:
      return ParseLinkHeader(frame, kSll2HeaderBytes, kSll2ProtocolOffset);
    case LinkLayer::kRawIp: return ParseRawIp(frame, /*ipv6_allowed=*/true);
    case LinkLayer::kRawIpv4: return ParseRawIp(frame, /*ipv6_allowed=*/false);
    case LinkLayer::kBsdLoopback: return ParseBsdLoopback(frame);
  }
  return Verdict(FrameVerdict::kMalformed);
}

}  // namespace flat2d::hal::net
