// A source of recorded UDP datagrams, and the one function that opens any capture.
//
// Offline tools and the replay code read pcap/pcapng captures and raw payload dumps
// through one interface, DatagramSource. OpenCapture picks the reader: (1) read the
// first four bytes; (2) a pcap (microsecond or nanosecond, either byte order) or
// pcapng magic number selects PcapReader; (3) otherwise a file whose size is a whole
// number of fixed-size records is taken as a raw payload dump; (4) anything else is
// an error naming the file and what it looked like.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "hal/common/error.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

// What a reader saw, so that a caller can tell a clean capture from a lossy one.
// Every frame ends up in exactly one of udp_datagrams, non_udp, fragments, malformed
// or truncated_frames.
struct CaptureStats {
  std::uint64_t frames = 0;            // records read from the file
  std::uint64_t udp_datagrams = 0;     // returned by Next()
  std::uint64_t non_udp = 0;           // not IPv4/UDP (ARP, IPv6, TCP, ...)
  std::uint64_t fragments = 0;         // IPv4 fragments of UDP datagrams
  std::uint64_t malformed = 0;         // inconsistent headers or lengths
  std::uint64_t truncated_frames = 0;  // cut by snaplen, or a partial raw record
  // Datagrams returned although their IPv4 total length ran past the frame (and
  // their UDP length did not); see frame_parser.hpp. Part of udp_datagrams.
  std::uint64_t ipv4_length_overruns = 0;
  bool file_truncated = false;         // reading stopped early on a damaged file
  std::string file_error;              // why, when file_truncated
};

class DatagramSource {
 public:
  virtual ~DatagramSource() = default;

  // The next datagram, or nullopt at the end (or at a damaged spot, see stats()).
  // The payload stays valid until the next call.
  virtual std::optional<UdpDatagram> Next() = 0;

  virtual const CaptureStats& stats() const = 0;

  // One line for logs, e.g. "pcap capture foo.pcap (EN10MB (1), ns timestamps)".
  virtual std::string Describe() const = 0;

 protected:
  DatagramSource() = default;
  DatagramSource(const DatagramSource&) = default;
  DatagramSource(DatagramSource&&) = default;
  DatagramSource& operator=(const DatagramSource&) = default;
  DatagramSource& operator=(DatagramSource&&) = default;
};

// Opens `path` as pcap/pcapng or as a raw dump of `raw_record_size`-byte payloads
// (1206 = a Velodyne data packet).
Result<std::unique_ptr<DatagramSource>> OpenCapture(const std::filesystem::path& path,
                                                    std::size_t raw_record_size = 1206);

}  // namespace flat2d::hal::net
