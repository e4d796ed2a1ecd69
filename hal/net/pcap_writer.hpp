// Writing UDP datagrams to a pcap file as synthesized Ethernet/IPv4/UDP frames.
//
// Recording a drive and building test captures both need a pcap that Wireshark,
// tcpdump and our own PcapReader read back exactly. Steps per datagram: (1) build an
// Ethernet header (broadcast and multicast destinations get their standard MACs,
// unicast ones a locally administered MAC derived from the IPv4 address); (2) build
// an IPv4 header with a valid header checksum and Don't Fragment set; (3) build a UDP
// header with checksum 0 ("not computed", legal for UDP over IPv4); (4) hand the frame
// to pcap_dump with the datagram's timestamp at the chosen precision. libpcap owns the
// file format; we own only the bytes of the frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/net/ipv4.hpp"
#include "hal/net/udp_datagram.hpp"

struct pcap;
struct pcap_dumper;

namespace flat2d::hal::net {

enum class TimestampPrecision {
  kMicrosecond,  // classic pcap (magic a1b2c3d4); nanoseconds are truncated
  kNanosecond,   // nanosecond pcap (magic a1b23c4d); exact
};

struct PcapWriterOptions {
  TimestampPrecision precision = TimestampPrecision::kNanosecond;
};

class PcapWriter {
 public:
  static Result<PcapWriter> Create(const std::filesystem::path& path,
                                   const PcapWriterOptions& options = {});

  PcapWriter(PcapWriter&&) noexcept = default;
  PcapWriter& operator=(PcapWriter&&) noexcept = default;
  ~PcapWriter() = default;  // closes silently; call Close() to learn about errors

  // Fails for payloads over kMaxUdpPayloadBytes, negative timestamps, or after Close().
  Status Write(const UdpDatagram& datagram);
  Status Flush();
  Status Close();

  std::uint64_t frames_written() const { return frames_written_; }

 private:
  struct DumperCloser {
    void operator()(pcap_dumper* dumper) const;
  };
  struct PcapCloser {
    void operator()(pcap* handle) const;
  };

  PcapWriter(std::unique_ptr<pcap, PcapCloser> handle,
             std::unique_ptr<pcap_dumper, DumperCloser> dumper,
             const PcapWriterOptions& options, std::filesystem::path path);

  std::unique_ptr<pcap, PcapCloser> handle_;
  std::unique_ptr<pcap_dumper, DumperCloser> dumper_;  // closed before handle_
  PcapWriterOptions options_;
  std::filesystem::path path_;
  // Sized once for the largest frame (14 + 20 + 8 + kMaxUdpPayloadBytes) so that
  // writing allocates nothing.
  std::vector<std::uint8_t> frame_;
  std::uint16_t next_ip_id_ = 0;
  std::uint64_t frames_written_ = 0;
};

}  // namespace flat2d::hal::net
