// IPv4 addresses and endpoints as text, and the IPv4/UDP size limit.
//
// Addresses travel through flat2d as host-order std::uint32_t (see Ipv4Endpoint);
// this header converts them from and to dotted-quad text ("192.168.1.201:2368") and
// names the few well-known ones, so that no caller hand-rolls inet_ntoa.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

inline constexpr std::uint32_t kIpv4Any = 0x00000000;        // 0.0.0.0
inline constexpr std::uint32_t kIpv4Loopback = 0x7F000001;   // 127.0.0.1
inline constexpr std::uint32_t kIpv4Broadcast = 0xFFFFFFFF;  // 255.255.255.255

inline constexpr std::size_t kEthernetHeaderBytes = 14;  // without VLAN tags
inline constexpr std::size_t kIpv4MinHeaderBytes = 20;  // without options
inline constexpr std::size_t kUdpHeaderBytes = 8;

// The largest payload one IPv4/UDP datagram can carry: 65535 - 20 (IPv4) - 8 (UDP).
inline constexpr std::size_t kMaxUdpPayloadBytes = 65507;

// "a.b.c.d" with each part 0..255 and no extra characters; nullopt otherwise.
std::optional<std::uint32_t> ParseIpv4(std::string_view text);

std::string FormatIpv4(std::uint32_t address);

// "a.b.c.d:port".
std::string FormatEndpoint(const Ipv4Endpoint& endpoint);

// 224.0.0.0/4.
constexpr bool IsIpv4Multicast(std::uint32_t address) { return (address >> 28) == 0xE; }

}  // namespace flat2d::hal::net
