#include "hal/net/pcap_writer.hpp"

#include <pcap/pcap.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <span>
#include <system_error>
#include <utility>

#include "hal/net/byte_order.hpp"
#include "hal/net/ipv4.hpp"

namespace flat2d::hal::net {
namespace {

constexpr std::size_t kHeaderBytes = kEthernetHeaderBytes + kIpv4MinHeaderBytes + kUdpHeaderBytes;
constexpr std::size_t kMaxFrameBytes = kHeaderBytes + kMaxUdpPayloadBytes;
constexpr std::uint8_t kIpv4DefaultTtl = 64;
constexpr std::uint16_t kIpv4DontFragment = 0x4000;

using Mac = std::array<std::uint8_t, 6>;

// Standard group MACs for broadcast (RFC 894) and multicast (RFC 1112: 01:00:5e +
// low 23 bits); a unicast address gets 02:00:a:b:c:d, locally administered, so that
// distinct hosts stay distinct in Wireshark.
Mac MacFor(std::uint32_t address) {
  if (address == kIpv4Broadcast) return {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  if (IsIpv4Multicast(address)) {
    return {0x01, 0x00, 0x5E, static_cast<std::uint8_t>((address >> 16) & 0x7F),
            static_cast<std::uint8_t>(address >> 8), static_cast<std::uint8_t>(address)};
  }
  return {0x02, 0x00, static_cast<std::uint8_t>(address >> 24),
          static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 8),
          static_cast<std::uint8_t>(address)};
}

// RFC 1071 one's-complement sum over the header, with the checksum field zero.
std::uint16_t Ipv4HeaderChecksum(std::span<const std::uint8_t> header) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < header.size(); i += 2) sum += LoadBe16(header, i);
  while ((sum >> 16) != 0) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

void WriteHeaders(std::span<std::uint8_t> frame, const UdpDatagram& datagram,
                  std::uint16_t ip_id) {
  const Mac destination_mac = MacFor(datagram.destination.address);
  const Mac source_mac = MacFor(datagram.source.address);
  std::memcpy(frame.data(), destination_mac.data(), destination_mac.size());
  std::memcpy(frame.data() + 6, source_mac.data(), source_mac.size());
  StoreBe16(frame, 12, 0x0800);  // EtherType IPv4

  const auto udp_length = static_cast<std::uint16_t>(kUdpHeaderBytes + datagram.payload.size());
  std::span<std::uint8_t> ip = frame.subspan(kEthernetHeaderBytes, kIpv4MinHeaderBytes);
  ip[0] = 0x45;  // version 4, IHL 5 words
  ip[1] = 0;     // DSCP/ECN
  StoreBe16(ip, 2, static_cast<std::uint16_t>(kIpv4MinHeaderBytes + udp_length));
  StoreBe16(ip, 4, ip_id);
  StoreBe16(ip, 6, kIpv4DontFragment);
  ip[8] = kIpv4DefaultTtl;
  ip[9] = 17;  // UDP
  StoreBe16(ip, 10, 0);
  StoreBe32(ip, 12, datagram.source.address);
  StoreBe32(ip, 16, datagram.destination.address);
  StoreBe16(ip, 10, Ipv4HeaderChecksum(ip));

  std::span<std::uint8_t> udp = frame.subspan(kEthernetHeaderBytes + kIpv4MinHeaderBytes);
  StoreBe16(udp, 0, datagram.source.port);
  StoreBe16(udp, 2, datagram.destination.port);
  StoreBe16(udp, 4, udp_length);
  StoreBe16(udp, 6, 0);  // checksum not computed
}

}  // namespace

void PcapWriter::DumperCloser::operator()(pcap_dumper* dumper) const { pcap_dump_close(dumper); }
void PcapWriter::PcapCloser::operator()(pcap* handle) const { pcap_close(handle); }

PcapWriter::PcapWriter(std::unique_ptr<pcap, PcapCloser> handle,
                       std::unique_ptr<pcap_dumper, DumperCloser> dumper,
                       const PcapWriterOptions& options, std::filesystem::path path)
    : handle_(std::move(handle)),
      dumper_(std::move(dumper)),
      options_(options),
      path_(std::move(path)),
      frame_(kMaxFrameBytes) {}

Result<PcapWriter> PcapWriter::Create(const std::filesystem::path& path,
                                      const PcapWriterOptions& options) {
  const u_int precision = options.precision == TimestampPrecision::kNanosecond
                              ? PCAP_TSTAMP_PRECISION_NANO
                              : PCAP_TSTAMP_PRECISION_MICRO;
  std::unique_ptr<pcap, PcapCloser> handle(pcap_open_dead_with_tstamp_precision(
      DLT_EN10MB, static_cast<int>(kMaxFrameBytes), precision));
  if (!handle) return MakeError("cannot create pcap " + path.string() + ": pcap_open_dead failed");
  std::unique_ptr<pcap_dumper, DumperCloser> dumper(pcap_dump_open(handle.get(), path.c_str()));
  if (!dumper) {
    return MakeError("cannot create pcap " + path.string() + ": " + pcap_geterr(handle.get()));
  }
  return PcapWriter(std::move(handle), std::move(dumper), options, path);
}

Status PcapWriter::Write(const UdpDatagram& datagram) {
  if (!dumper_) return MakeError("pcap " + path_.string() + " is closed");
  if (datagram.payload.size() > kMaxUdpPayloadBytes) {
    return MakeError("cannot write a UDP payload of " + std::to_string(datagram.payload.size()) +
                     " bytes (IPv4 limit 65507) to " + path_.string());
  }
  if (datagram.receive_time_ns < 0) {
    return MakeError("cannot write a timestamp before 1970 to " + path_.string());
  }
  WriteHeaders(frame_, datagram, next_ip_id_++);
  if (!datagram.payload.empty()) {
    std::memcpy(frame_.data() + kHeaderBytes, datagram.payload.data(), datagram.payload.size());
  }
  pcap_pkthdr header{};
  header.ts.tv_sec = datagram.receive_time_ns / kNsPerSecond;
  const TimeNs fraction_ns = datagram.receive_time_ns % kNsPerSecond;
  // The dead handle's precision tells pcap_dump how to read tv_usec.
  header.ts.tv_usec = options_.precision == TimestampPrecision::kNanosecond
                          ? fraction_ns
                          : fraction_ns / kNsPerUs;
  header.caplen = header.len = static_cast<bpf_u_int32>(kHeaderBytes + datagram.payload.size());
  pcap_dump(reinterpret_cast<u_char*>(dumper_.get()), &header, frame_.data());
  ++frames_written_;
  return Status::Ok();
}

Status PcapWriter::Flush() {
  if (!dumper_) return MakeError("pcap " + path_.string() + " is closed");
  // pcap_dump reports nothing itself; a failed write shows up in the stream state.
  if (pcap_dump_flush(dumper_.get()) != 0 || std::ferror(pcap_dump_file(dumper_.get())) != 0) {
    return MakeError("cannot write pcap " + path_.string() + ": " +
                     std::system_category().message(errno));
  }
  return Status::Ok();
}

Status PcapWriter::Close() {
  if (!dumper_) return Status::Ok();
  Status flushed = Flush();
  dumper_.reset();
  handle_.reset();
  return flushed;
}

}  // namespace flat2d::hal::net
