#include "hal/net/pcap_reader.hpp"

#include <pcap/pcap.h>

#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>

namespace flat2d::hal::net {
namespace {

// Seconds + nanoseconds as TimeNs, or nullopt if a corrupt record overflows int64
// (pcapng timestamps are 64-bit in arbitrary units, so seconds can be huge).
std::optional<TimeNs> ToTimeNs(TimeNs seconds, TimeNs nanoseconds) {
  TimeNs scaled = 0;
  TimeNs total = 0;
  if (__builtin_mul_overflow(seconds, kNsPerSecond, &scaled) ||
      __builtin_add_overflow(scaled, nanoseconds, &total)) {
    return std::nullopt;
  }
  return total;
}

}  // namespace

void PcapReader::PcapCloser::operator()(pcap* handle) const { pcap_close(handle); }

PcapReader::PcapReader(Handle handle, std::unique_ptr<std::vector<std::uint8_t>> image,
                       int dlt, LinkLayer link, std::string name)
    : image_(std::move(image)),
      handle_(std::move(handle)),
      dlt_(dlt),
      link_(link),
      name_(std::move(name)) {}

Result<PcapReader> PcapReader::Open(const std::filesystem::path& path) {
  char error_text[PCAP_ERRBUF_SIZE] = {};
  pcap_t* handle = pcap_open_offline_with_tstamp_precision(
      path.c_str(), PCAP_TSTAMP_PRECISION_NANO, error_text);
  if (handle == nullptr) {
    return MakeError("cannot open capture " + path.string() + ": " + error_text);
  }
  return FromHandle(Handle(handle), nullptr, path.string());
}

Result<PcapReader> PcapReader::OpenMemory(std::span<const std::uint8_t> bytes) {
  // fmemopen refuses a zero-sized buffer, and an empty image is no capture anyway.
  if (bytes.empty()) return MakeError("cannot open in-memory capture: it is empty");
  auto image = std::make_unique<std::vector<std::uint8_t>>(bytes.begin(), bytes.end());
  std::FILE* file = fmemopen(image->data(), image->size(), "rb");
  if (file == nullptr) {
    return MakeError("cannot open in-memory capture: fmemopen: " +
                     std::system_category().message(errno));
  }
  char error_text[PCAP_ERRBUF_SIZE] = {};
  pcap_t* handle =
      pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_NANO, error_text);
  if (handle == nullptr) {
    std::fclose(file);  // libpcap takes ownership of the FILE only on success
    return MakeError(std::string("cannot open in-memory capture: ") + error_text);
  }
  const std::string name = "in-memory capture of " + std::to_string(bytes.size()) + " bytes";
  return FromHandle(Handle(handle), std::move(image), name);
}

Result<PcapReader> PcapReader::FromHandle(Handle handle,
                                          std::unique_ptr<std::vector<std::uint8_t>> image,
                                          std::string name) {
  const int dlt = pcap_datalink(handle.get());
  const std::optional<LinkLayer> link = LinkLayerFromDlt(dlt);
  if (!link) {
    return MakeError(name + ": unsupported link type " + DescribeDlt(dlt) +
                     "; UDP can be read from Ethernet, Linux SLL/SLL2, raw IP and BSD "
                     "loopback captures");
  }
  return PcapReader(std::move(handle), std::move(image), dlt, *link, std::move(name));
}

std::optional<UdpDatagram> PcapReader::Next() {
  while (!finished_) {
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    const int status = pcap_next_ex(handle_.get(), &header, &data);
    if (status == 1) {
      // With nanosecond precision libpcap puts nanoseconds in tv_usec.
      std::optional<UdpDatagram> datagram =
          Classify(header->ts.tv_sec, header->ts.tv_usec, {data, header->caplen},
                   header->caplen < header->len);
      if (datagram) return datagram;
      continue;
    }
    finished_ = true;
    // PCAP_ERROR_BREAK is how an offline handle says "end of file"; anything else
    // is a damaged or cut file, reported in the stats rather than thrown.
    if (status != PCAP_ERROR_BREAK) {
      stats_.file_truncated = true;
      stats_.file_error = pcap_geterr(handle_.get());
    }
  }
  return std::nullopt;
}

std::optional<UdpDatagram> PcapReader::Classify(TimeNs seconds, TimeNs nanoseconds,
                                                std::span<const std::uint8_t> frame,
                                                bool cut) {
  ++stats_.frames;
  if (cut) {
    ++stats_.truncated_frames;
    return std::nullopt;
  }
  const ParsedFrame parsed = ParseFrame(link_, frame);
  const std::optional<TimeNs> receive_time_ns = ToTimeNs(seconds, nanoseconds);
  switch (parsed.verdict) {
    case FrameVerdict::kNotUdp: ++stats_.non_udp; return std::nullopt;
    case FrameVerdict::kFragment: ++stats_.fragments; return std::nullopt;
    case FrameVerdict::kMalformed: ++stats_.malformed; return std::nullopt;
    case FrameVerdict::kUdp: break;
  }
  if (!receive_time_ns) {
    ++stats_.malformed;
    return std::nullopt;
  }
  ++stats_.udp_datagrams;
  if (parsed.ipv4_length_overrun) ++stats_.ipv4_length_overruns;
  return UdpDatagram{*receive_time_ns, parsed.source, parsed.destination, parsed.payload};
}

std::string PcapReader::Describe() const {
  return "pcap capture " + name_ + " (link type " + DescribeDlt(dlt_) + ")";
}

}  // namespace flat2d::hal::net
