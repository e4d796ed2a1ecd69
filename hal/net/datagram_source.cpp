#include "hal/net/datagram_source.hpp"

#include <array>
#include <cstdio>
#include <system_error>

#include "hal/net/byte_order.hpp"
#include "hal/net/pcap_reader.hpp"
#include "hal/net/raw_payload_reader.hpp"

namespace flat2d::hal::net {
namespace {

// The first four file bytes read as big-endian: pcap in both byte orders with
// microsecond (a1b2c3d4) or nanosecond (a1b23c4d) timestamps, and the pcapng Section
// Header Block type (0a0d0d0a, a palindrome).
bool IsCaptureMagic(std::uint32_t magic) {
  return magic == 0xA1B2C3D4 || magic == 0xD4C3B2A1 || magic == 0xA1B23C4D ||
         magic == 0x4D3CB2A1 || magic == 0x0A0D0D0A;
}

std::optional<std::uint32_t> ReadMagic(const std::filesystem::path& path) {
  std::array<std::uint8_t, 4> bytes{};
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return std::nullopt;
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), file);
  std::fclose(file);
  if (got != bytes.size()) return std::nullopt;
  return LoadBe32(bytes, 0);
}

}  // namespace

Result<std::unique_ptr<DatagramSource>> OpenCapture(const std::filesystem::path& path,
                                                    std::size_t raw_record_size) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return MakeError("cannot open capture " + path.string() + ": " + error.message());
  const std::optional<std::uint32_t> magic = ReadMagic(path);
  if (magic && IsCaptureMagic(*magic)) {
    Result<PcapReader> reader = PcapReader::Open(path);
    if (!reader) return reader.error();
    return std::unique_ptr<DatagramSource>(
        std::make_unique<PcapReader>(std::move(reader).value()));
  }
  if (raw_record_size > 0 && size > 0 && size % raw_record_size == 0) {
    RawPayloadOptions options;
    options.record_size = raw_record_size;
    Result<RawPayloadReader> reader = RawPayloadReader::Open(path, options);
    if (!reader) return reader.error();
    return std::unique_ptr<DatagramSource>(
        std::make_unique<RawPayloadReader>(std::move(reader).value()));
  }
  return MakeError("cannot open capture " + path.string() + ": not pcap or pcapng (no magic "
                   "number) and its " + std::to_string(size) +
                   " bytes are not a whole number of " + std::to_string(raw_record_size) +
                   "-byte raw payloads");
}

}  // namespace flat2d::hal::net
