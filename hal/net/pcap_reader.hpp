// Reading UDP datagrams from pcap and pcapng capture files with libpcap.
//
// libpcap parses both container formats and, asked for nanosecond precision, scales
// every timestamp to nanoseconds. Steps: (1) open the file (or an in-memory image,
// for fuzzing) and refuse link types we cannot read UDP from, naming them; (2) for
// each record, skip frames cut by the snaplen, because a partial Velodyne packet is
// worse than none; (3) decode link -> IPv4 -> UDP (frame_parser.hpp) and count every
// frame that is not a whole IPv4/UDP datagram; (4) stop at the end of file, or at a
// damaged record, which sets stats().file_truncated and keeps what was read before.
// Nothing is copied: a datagram's payload points into libpcap's record buffer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/net/frame_parser.hpp"
#include "hal/net/udp_datagram.hpp"

struct pcap;  // libpcap's pcap_t; its header stays out of ours

namespace flat2d::hal::net {

using PcapStats = CaptureStats;

class PcapReader final : public DatagramSource {
 public:
  static Result<PcapReader> Open(const std::filesystem::path& path);

  // Reads a capture image held in memory (tests, fuzzing); the bytes are copied.
  static Result<PcapReader> OpenMemory(std::span<const std::uint8_t> bytes);

  PcapReader(PcapReader&&) noexcept = default;
  PcapReader& operator=(PcapReader&&) noexcept = default;
  ~PcapReader() override = default;

  std::optional<UdpDatagram> Next() override;
  const CaptureStats& stats() const override { return stats_; }
  std::string Describe() const override;

  // The libpcap DLT value of the capture, e.g. 1 for Ethernet.
  int link_type() const { return dlt_; }

 private:
  struct PcapCloser {
    void operator()(pcap* handle) const;
  };
  using Handle = std::unique_ptr<pcap, PcapCloser>;

  PcapReader(Handle handle, std::unique_ptr<std::vector<std::uint8_t>> image, int dlt,
             LinkLayer link, std::string name);
  static Result<PcapReader> FromHandle(Handle handle,
                                       std::unique_ptr<std::vector<std::uint8_t>> image,
                                       std::string name);
  std::optional<UdpDatagram> Classify(TimeNs seconds, TimeNs nanoseconds,
                                      std::span<const std::uint8_t> frame, bool cut);

  // Declared before handle_ so that it outlives it: libpcap reads the in-memory image
  // through an fmemopen FILE until pcap_close.
  std::unique_ptr<std::vector<std::uint8_t>> image_;
  Handle handle_;
  int dlt_ = 0;
  LinkLayer link_ = LinkLayer::kEthernet;
  std::string name_;
  bool finished_ = false;
  CaptureStats stats_;
};

}  // namespace flat2d::hal::net
