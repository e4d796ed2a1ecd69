#include "tests/hal/net/capture_images.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

namespace flat2d::hal::net::testing {
namespace {

void PutBe16(Bytes& bytes, std::uint16_t value) {
  bytes.push_back(static_cast<std::uint8_t>(value >> 8));
  bytes.push_back(static_cast<std::uint8_t>(value));
}
void PutBe32(Bytes& bytes, std::uint32_t value) {
  PutBe16(bytes, static_cast<std::uint16_t>(value >> 16));
  PutBe16(bytes, static_cast<std::uint16_t>(value));
}
void PutLe16(Bytes& bytes, std::uint16_t value) {
  bytes.push_back(static_cast<std::uint8_t>(value));
  bytes.push_back(static_cast<std::uint8_t>(value >> 8));
}
void PutLe32(Bytes& bytes, std::uint32_t value) {
  PutLe16(bytes, static_cast<std::uint16_t>(value));
  PutLe16(bytes, static_cast<std::uint16_t>(value >> 16));
}
void Append(Bytes& bytes, const Bytes& tail) {
  bytes.insert(bytes.end(), tail.begin(), tail.end());
}

std::uint16_t Checksum(const Bytes& header) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < header.size(); i += 2) sum += (header[i] << 8) | header[i + 1];
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

void PadTo4(Bytes& bytes) {
  while (bytes.size() % 4 != 0) bytes.push_back(0);
}

}  // namespace

Bytes Ipv4Udp(const Ipv4Endpoint& source, const Ipv4Endpoint& destination, const Bytes& payload,
              const Ipv4Shape& shape) {
  const std::size_t header_bytes = 20;  // options (if IHL > 5) are zero bytes
  const std::size_t options_bytes = shape.ihl_words > 5 ? (shape.ihl_words - 5) * 4u : 0u;
  const auto udp_length = static_cast<std::uint16_t>(8 + payload.size());
  Bytes ip;
  ip.push_back(static_cast<std::uint8_t>(0x40 | shape.ihl_words));
  ip.push_back(0);
  PutBe16(ip, static_cast<std::uint16_t>(header_bytes + options_bytes + udp_length +
                                         shape.ipv4_total_length_delta));
  PutBe16(ip, 0x1234);
  PutBe16(ip, shape.flags_and_fragment_offset);
  ip.push_back(64);
  ip.push_back(shape.protocol);
  PutBe16(ip, 0);
  PutBe32(ip, source.address);
  PutBe32(ip, destination.address);
  ip.resize(header_bytes + options_bytes, 0);
  const std::uint16_t checksum = Checksum(ip);
  ip[10] = static_cast<std::uint8_t>(checksum >> 8);
  ip[11] = static_cast<std::uint8_t>(checksum);
  PutBe16(ip, source.port);
  PutBe16(ip, destination.port);
  PutBe16(ip, static_cast<std::uint16_t>(udp_length + shape.udp_length_delta));
  PutBe16(ip, 0);
  Append(ip, payload);
  return ip;
}

Bytes EthernetFrame(const Bytes& packet, std::uint16_t ether_type,
                    const std::vector<VlanTag>& tags) {
  Bytes frame = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x60, 0x76, 0x88, 0x00, 0x00, 0x01};
  for (const VlanTag& tag : tags) {
    PutBe16(frame, tag.ether_type);
    PutBe16(frame, tag.tci);
  }
  PutBe16(frame, ether_type);
  Append(frame, packet);
  return frame;
}

Bytes SllFrame(const Bytes& packet, std::uint16_t protocol) {
  Bytes frame;
  PutBe16(frame, 0);  // packet type: to us
  PutBe16(frame, 1);  // ARPHRD_ETHER
  PutBe16(frame, 6);  // address length
  Append(frame, {0x60, 0x76, 0x88, 0x00, 0x00, 0x01, 0x00, 0x00});
  PutBe16(frame, protocol);
  Append(frame, packet);
  return frame;
}

Bytes Sll2Frame(const Bytes& packet, std::uint16_t protocol) {
  Bytes frame;
  PutBe16(frame, protocol);
  PutBe16(frame, 0);  // reserved
  PutBe32(frame, 3);  // interface index
  PutBe16(frame, 1);  // ARPHRD_ETHER
  frame.push_back(0);  // packet type
  frame.push_back(6);  // address length
  Append(frame, {0x60, 0x76, 0x88, 0x00, 0x00, 0x01, 0x00, 0x00});
  Append(frame, packet);
  return frame;
}

Bytes BsdLoopbackFrame(const Bytes& packet, std::uint32_t family, bool big_endian) {
  Bytes frame;
  if (big_endian) {
    PutBe32(frame, family);
  } else {
    PutLe32(frame, family);
  }
  Append(frame, packet);
  return frame;
}

Bytes PcapImage(std::uint32_t link_type, const std::vector<Record>& records, bool nanosecond) {
  Bytes image;
  PutLe32(image, nanosecond ? 0xA1B23C4D : 0xA1B2C3D4);
  PutLe16(image, 2);
  PutLe16(image, 4);
  PutLe32(image, 0);  // thiszone
  PutLe32(image, 0);  // sigfigs
  PutLe32(image, 65535);
  PutLe32(image, link_type);
  for (const Record& record : records) {
    PutLe32(image, record.seconds);
    PutLe32(image, record.fraction);
    PutLe32(image, static_cast<std::uint32_t>(record.frame.size()));
    PutLe32(image, record.original_length != 0 ? record.original_length
                                               : static_cast<std::uint32_t>(record.frame.size()));
    Append(image, record.frame);
  }
  return image;
}

Bytes PcapngImage(std::uint32_t link_type, const std::vector<Record>& records, bool nanosecond) {
  Bytes image;
  // Section Header Block: type, length, byte-order magic, version 1.0, section length -1.
  PutLe32(image, 0x0A0D0D0A);
  PutLe32(image, 28);
  PutLe32(image, 0x1A2B3C4D);
  PutLe16(image, 1);
  PutLe16(image, 0);
  PutLe32(image, 0xFFFFFFFF);
  PutLe32(image, 0xFFFFFFFF);
  PutLe32(image, 28);
  // Interface Description Block, with if_tsresol = 9 (10^-9 s) for nanoseconds.
  const std::uint32_t idb_length = nanosecond ? 32 : 20;
  PutLe32(image, 1);
  PutLe32(image, idb_length);
  PutLe16(image, static_cast<std::uint16_t>(link_type));
  PutLe16(image, 0);
  PutLe32(image, 65535);
  if (nanosecond) {
    PutLe16(image, 9);  // if_tsresol
    PutLe16(image, 1);
    Append(image, {9, 0, 0, 0});
    PutLe32(image, 0);  // opt_endofopt
  }
  PutLe32(image, idb_length);
  for (const Record& record : records) {
    const std::uint64_t units_per_second = nanosecond ? 1'000'000'000 : 1'000'000;
    const std::uint64_t timestamp = record.seconds * units_per_second + record.fraction;
    Bytes block;
    PutLe32(block, 0);  // interface id
    PutLe32(block, static_cast<std::uint32_t>(timestamp >> 32));
    PutLe32(block, static_cast<std::uint32_t>(timestamp));
    PutLe32(block, static_cast<std::uint32_t>(record.frame.size()));
    PutLe32(block, record.original_length != 0 ? record.original_length
                                               : static_cast<std::uint32_t>(record.frame.size()));
    Append(block, record.frame);
    PadTo4(block);
    const auto total = static_cast<std::uint32_t>(block.size() + 12);
    PutLe32(image, 6);  // Enhanced Packet Block
    PutLe32(image, total);
    Append(image, block);
    PutLe32(image, total);
  }
  return image;
}

Bytes PayloadOf(const UdpDatagram& datagram) {
  return Bytes(datagram.payload.begin(), datagram.payload.end());
}

Bytes CountingPayload(std::size_t size, std::uint8_t first) {
  Bytes payload(size);
  for (std::size_t i = 0; i < size; ++i) payload[i] = static_cast<std::uint8_t>(first + i);
  return payload;
}

std::filesystem::path TempPath(const std::string& name) {
  // The pid keeps parallel test processes (ctest -j) from sharing a file.
  return std::filesystem::path(::testing::TempDir()) / (std::to_string(::getpid()) + "_" + name);
}

std::filesystem::path WriteTempFile(const std::string& name, const Bytes& bytes) {
  const std::filesystem::path path = TempPath(name);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  return path;
}

}  // namespace flat2d::hal::net::testing
