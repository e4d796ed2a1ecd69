#include "hal/net/ipv4.hpp"

#include <charconv>

namespace flat2d::hal::net {

std::optional<std::uint32_t> ParseIpv4(std::string_view text) {
  std::uint32_t address = 0;
  const char* cursor = text.data();
  const char* const end = text.data() + text.size();
  for (int part = 0; part < 4; ++part) {
    if (part > 0) {
      if (cursor == end || *cursor != '.') return std::nullopt;
      ++cursor;
    }
    // from_chars accepts neither signs nor spaces, which is what we want here.
    unsigned value = 0;
    const auto [next, error] = std::from_chars(cursor, end, value);
    if (error != std::errc{} || next == cursor || next - cursor > 3 || value > 255) {
      return std::nullopt;
    }
    address = (address << 8) | value;
    cursor = next;
  }
  if (cursor != end) return std::nullopt;
  return address;
}

std::string FormatIpv4(std::uint32_t address) {
  return std::to_string(address >> 24) + '.' + std::to_string((address >> 16) & 0xFF) + '.' +
         std::to_string((address >> 8) & 0xFF) + '.' + std::to_string(address & 0xFF);
}

std::string FormatEndpoint(const Ipv4Endpoint& endpoint) {
  return FormatIpv4(endpoint.address) + ':' + std::to_string(endpoint.port);
}

}  // namespace flat2d::hal::net
