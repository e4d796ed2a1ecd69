#include "hal/net/raw_payload_reader.hpp"

#include <cerrno>
#include <system_error>
#include <utility>


namespace flat2d::hal::net {

RawPayloadReader::RawPayloadReader(std::unique_ptr<std::FILE, FileCloser> file,
                                   const RawPayloadOptions& options, std::filesystem::path path)
    : file_(std::move(file)),
      options_(options),
      path_(std::move(path)),
      record_(options.record_size) {}

Result<RawPayloadReader> RawPayloadReader::Open(const std::filesystem::path& path,
                                                const RawPayloadOptions& options) {
  if (options.record_size == 0 || options.record_size > kMaxUdpPayloadBytes) {
    return MakeError("cannot read raw payloads from " + path.string() + ": record size " +
                     std::to_string(options.record_size) + " is not 1..65507 bytes");
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    return MakeError("cannot open raw payload dump " + path.string() + ": " +
                     std::system_category().message(errno));
  }
  return RawPayloadReader(std::move(file), options, path);
}

std::optional<UdpDatagram> RawPayloadReader::Next() {
  if (finished_) return std::nullopt;
  const std::size_t got = std::fread(record_.data(), 1, record_.size(), file_.get());
  if (got == record_.size()) {
    ++stats_.frames;
    ++stats_.udp_datagrams;
    return UdpDatagram{0, options_.source, options_.destination, record_};
  }
  finished_ = true;
  if (std::ferror(file_.get()) != 0) {
    stats_.file_truncated = true;
    stats_.file_error = "read error in " + path_.string();
  } else if (got > 0) {
    ++stats_.frames;
    ++stats_.truncated_frames;
    stats_.file_truncated = true;
    stats_.file_error = "trailing partial record of " + std::to_string(got) +
                        " bytes (record size " + std::to_string(record_.size()) + ") in " +
                        path_.string();
  }
  return std::nullopt;
}

std::string RawPayloadReader::Describe() const {
  return "raw payload dump " + path_.string() + " (" + std::to_string(options_.record_size) +
         "-byte records, no timestamps)";
}

}  // namespace flat2d::hal::net
