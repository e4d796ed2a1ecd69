#include "hal/can/candump_log.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

namespace flat2d::hal::can {
namespace {

// The read window: one fread fills it; it must hold at least one whole longest line.
constexpr std::size_t kReadBlockBytes = 64 * 1024;
static_assert(kReadBlockBytes > 2 * kMaxCandumpLineBytes);

std::string ErrnoText(int error_number) { return std::system_category().message(error_number); }

}  // namespace

std::uint64_t CandumpReaderStats::FramesOn(std::string_view name) const {
  for (const CandumpInterfaceFrames& counted : interfaces) {
    if (counted.name == name) return counted.frames;
  }
  return 0;
}

CandumpReader::CandumpReader(std::unique_ptr<std::FILE, FileCloser> file,
                             std::string buffer, bool end_of_input, std::string name)
    : file_(std::move(file)),
      buffer_(std::move(buffer)),
      end_(end_of_input ? buffer_.size() : 0),
      end_of_input_(end_of_input),
      name_(std::move(name)) {
  stats_.first_malformed.reserve(kMaxRecordedMalformedLines);
  stats_.interfaces.reserve(kMaxCountedInterfaces);
}

Result<CandumpReader> CandumpReader::Open(const std::filesystem::path& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return MakeError("cannot open candump log " + path.string() + ": " + ErrnoText(errno));
  return CandumpReader(std::move(file), std::string(kReadBlockBytes, '\0'), false, path.string());
}

CandumpReader CandumpReader::FromString(std::string text, std::string name) {
  return CandumpReader(nullptr, std::move(text), true, std::move(name));
}

bool CandumpReader::Next(CanFrame& frame) {
  std::string_view line;
  bool too_long = false;
  while (NextLine(line, too_long)) {
    ++stats_.lines;
    if (too_long) {
      CountMalformed(CandumpError::kLineTooLong);
      continue;
    }
    const CandumpLine parsed = ParseCandumpLine(line, frame);
    switch (parsed.kind) {
      case CandumpLineKind::kFrame: CountFrame(frame, parsed.direction); return true;
      case CandumpLineKind::kIgnored: ++stats_.ignored_lines; break;
      case CandumpLineKind::kDropNotice: ++stats_.drop_notices; break;
      case CandumpLineKind::kMalformed: CountMalformed(parsed.error); break;
    }
  }
  return false;
}

// The next line without its '\n', viewing buffer_ until the next call; false at the end.
// A line that outgrew the window comes back once, as its tail, with too_long set.
bool CandumpReader::NextLine(std::string_view& line, bool& too_long) {
  for (;;) {
    const char* start = buffer_.data() + begin_;
    const std::size_t available = end_ - begin_;
    const auto* newline =
        available == 0 ? nullptr : static_cast<const char*>(std::memchr(start, '\n', available));
    if (newline != nullptr || end_of_input_) {
      if (newline == nullptr && available == 0 && !skipping_long_line_) return false;
      const std::size_t length = newline != nullptr ? static_cast<std::size_t>(newline - start)
                                                    : available;
      line = {start, length};
      begin_ += length + (newline != nullptr ? 1 : 0);
      too_long = skipping_long_line_ || length > kMaxCandumpLineBytes;
      skipping_long_line_ = false;
      return true;
    }
    Refill();
  }
}

void CandumpReader::Refill() {
  if (end_ - begin_ > kMaxCandumpLineBytes) {
    // Already too long to be a line: drop it and remember to skip to its end.
    skipping_long_line_ = true;
    begin_ = end_ = 0;
  } else {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t read = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_.get());
  end_ += read;
  if (read == 0) {
    end_of_input_ = true;
    if (std::ferror(file_.get()) != 0) stats_.read_error = "read error in " + name_;
  }
}

void CandumpReader::CountMalformed(CandumpError error) {
  ++stats_.malformed;
  if (stats_.first_malformed.size() < kMaxRecordedMalformedLines) {
    stats_.first_malformed.push_back({stats_.lines, error});
  }
}

void CandumpReader::CountFrame(const CanFrame& frame, CandumpDirection direction) {
  last_direction_ = direction;
  ++stats_.frames;
  if (frame.error) ++stats_.error_frames;
  if (frame.remote) ++stats_.remote_frames;
  if (frame.fd) ++stats_.fd_frames;
  if (direction == CandumpDirection::kTransmitted) ++stats_.transmitted;
  const std::string_view name = frame.interface_name();
  for (CandumpInterfaceFrames& counted : stats_.interfaces) {
    if (counted.name == name) {
      ++counted.frames;
      return;
    }
  }
  if (stats_.interfaces.size() < kMaxCountedInterfaces) {
    stats_.interfaces.push_back({std::string(name), 1});
  } else {
    ++stats_.other_interface_frames;
  }
}

CandumpWriter::CandumpWriter(std::unique_ptr<std::FILE, FileCloser> file,
                             CandumpWriterOptions options, std::string path)
    : file_(std::move(file)), options_(std::move(options)), path_(std::move(path)) {}

Result<CandumpWriter> CandumpWriter::Open(const std::filesystem::path& path,
                                          CandumpWriterOptions options) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) {
    return MakeError("cannot create candump log " + path.string() + ": " + ErrnoText(errno));
  }
  return CandumpWriter(std::move(file), std::move(options), path.string());
}

Status CandumpWriter::Write(const CanFrame& frame, CandumpDirection direction) {
  if (!file_) return MakeError("candump log " + path_ + " is closed");
  const CandumpFormat format{options_.seconds_digits, options_.interface_width,
                             options_.fallback_interface};
  std::array<char, kMaxCandumpFormattedBytes> text{};
  const CandumpFormatted line = FormatCandumpLine(frame, format, direction, text);
  if (line.size == 0) {
    return MakeError("cannot write frame " + std::string(FormatCanId(frame).data()) + " to " +
                     path_ + ": " + std::string(line.error));
  }
  if (std::fwrite(text.data(), 1, line.size, file_.get()) != line.size) {
    return MakeError("cannot write to candump log " + path_ + ": " + ErrnoText(errno));
  }
  ++frames_written_;
  return Status::Ok();
}

Status CandumpWriter::Close() {
  if (!file_) return Status::Ok();
  const bool failed = std::ferror(file_.get()) != 0;
  const int close_result = std::fclose(file_.release());
  if (failed || close_result != 0) {
    return MakeError("cannot finish candump log " + path_ + ": " + ErrnoText(errno));
  }
  return Status::Ok();
}

}  // namespace flat2d::hal::can
