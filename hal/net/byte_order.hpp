// Explicit byte-order loads and stores for wire formats.
//
// Network headers are big-endian and pcap link headers are sometimes little-endian;
// reading them byte by byte keeps the code independent of host order and of the
// alignment of the capture buffer (no reinterpret_cast of packet bytes anywhere).
// Callers check bounds first: these functions assume offset + width <= bytes.size().
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace flat2d::hal::net {

inline std::uint16_t LoadBe16(std::span<const std::uint8_t> bytes, std::size_t offset) {
  return static_cast<std::uint16_t>((bytes[offset] << 8) | bytes[offset + 1]);
}

inline std::uint32_t LoadBe32(std::span<const std::uint8_t> bytes, std::size_t offset) {
  return (std::uint32_t{bytes[offset]} << 24) | (std::uint32_t{bytes[offset + 1]} << 16) |
         (std::uint32_t{bytes[offset + 2]} << 8) | std::uint32_t{bytes[offset + 3]};
}

inline std::uint32_t LoadLe32(std::span<const std::uint8_t> bytes, std::size_t offset) {
  return (std::uint32_t{bytes[offset + 3]} << 24) | (std::uint32_t{bytes[offset + 2]} << 16) |
         (std::uint32_t{bytes[offset + 1]} << 8) | std::uint32_t{bytes[offset]};
}

inline void StoreBe16(std::span<std::uint8_t> bytes, std::size_t offset, std::uint16_t value) {
  bytes[offset] = static_cast<std::uint8_t>(value >> 8);
  bytes[offset + 1] = static_cast<std::uint8_t>(value);
}

inline void StoreBe32(std::span<std::uint8_t> bytes, std::size_t offset, std::uint32_t value) {
  StoreBe16(bytes, offset, static_cast<std::uint16_t>(value >> 16));
  StoreBe16(bytes, offset + 2, static_cast<std::uint16_t>(value));
}

}  // namespace flat2d::hal::net
