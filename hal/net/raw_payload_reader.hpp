// Reading dumps of back-to-back fixed-size UDP payloads with no headers at all.
//
// Some Velodyne tools record only the 1206-byte data payloads, one after another,
// without link headers or host timestamps. Steps: (1) open the file and check the
// record size; (2) read one record per Next() into a buffer sized once at Open;
// (3) stamp it with receive_time_ns = 0, since no host time exists (the device time
// inside the payload is the decoder's business), and with the endpoints from the
// options; (4) a trailing partial record is counted as truncated and ends the file.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/net/ipv4.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

struct RawPayloadOptions {
  std::size_t record_size = 1206;  // a Velodyne data packet
  // The dump does not say where the payloads came from or went to. The default
  // destination is the Velodyne data port, so that port filters (replay) keep them.
  Ipv4Endpoint source{};
  Ipv4Endpoint destination{kIpv4Broadcast, 2368};
};

class RawPayloadReader final : public DatagramSource {
 public:
  static Result<RawPayloadReader> Open(const std::filesystem::path& path,
                                       const RawPayloadOptions& options = {});

  RawPayloadReader(RawPayloadReader&&) noexcept = default;
  RawPayloadReader& operator=(RawPayloadReader&&) noexcept = default;
  ~RawPayloadReader() override = default;

  std::optional<UdpDatagram> Next() override;
  const CaptureStats& stats() const override { return stats_; }
  std::string Describe() const override;

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  RawPayloadReader(std::unique_ptr<std::FILE, FileCloser> file,
                   const RawPayloadOptions& options, std::filesystem::path path);

  std::unique_ptr<std::FILE, FileCloser> file_;
  RawPayloadOptions options_;
  std::filesystem::path path_;
  std::vector<std::uint8_t> record_;  // one record; options_.record_size bytes
  bool finished_ = false;
  CaptureStats stats_;
};

}  // namespace flat2d::hal::net
