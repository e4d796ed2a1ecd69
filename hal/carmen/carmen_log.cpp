#include "hal/carmen/carmen_log.hpp"

#include <zlib.h>

#include <array>
#include <utility>

#include "hal/carmen/carmen_line.hpp"

namespace flat2d::hal::carmen {

// Where lines come from: a gzip (or plain) file through zlib, or text in memory.
struct CarmenLogReader::Source {
  gzFile file = nullptr;
  std::string text;
  std::size_t position = 0;

  ~Source() {
    if (file != nullptr) gzclose(file);
  }

  // Appends up to one line (without its newline) to `line`; false at the end.
  // `complete` is false when the line continues past what was read.
  bool Read(std::string& line, bool& complete, std::string& error) {
    return file != nullptr ? ReadFile(line, complete, error) : ReadText(line, complete);
  }

  bool ReadText(std::string& line, bool& complete) {
    if (position >= text.size()) return false;
    std::size_t end = text.find('\n', position);
    complete = true;
    if (end == std::string::npos) end = text.size();
    line.append(text, position, end - position);
    position = end + 1;
    return true;
  }

  bool ReadFile(std::string& line, bool& complete, std::string& error) {
    std::array<char, 65536> chunk{};
    if (gzgets(file, chunk.data(), static_cast<int>(chunk.size())) == nullptr) {
      int code = Z_OK;
      const char* message = gzerror(file, &code);
      if (code != Z_OK && code != Z_STREAM_END) error = message;
      return false;
    }
    std::string_view read(chunk.data());
    complete = !read.empty() && read.back() == '\n';
    if (complete) read.remove_suffix(1);
    if (!complete && gzeof(file)) complete = true;  // last line without a newline
    line.append(read);
    return true;
  }
};

CarmenLogReader::CarmenLogReader(std::unique_ptr<Source> source, std::string name)
    : source_(std::move(source)), name_(std::move(name)) {}
CarmenLogReader::CarmenLogReader(CarmenLogReader&&) noexcept = default;
CarmenLogReader& CarmenLogReader::operator=(CarmenLogReader&&) noexcept = default;
CarmenLogReader::~CarmenLogReader() = default;

Result<CarmenLogReader> CarmenLogReader::Open(const std::filesystem::path& path) {
  auto source = std::make_unique<Source>();
  source->file = gzopen(path.c_str(), "rb");
  if (source->file == nullptr) return MakeError("cannot open CARMEN log " + path.string());
  return CarmenLogReader(std::move(source), path.string());
}

CarmenLogReader CarmenLogReader::FromString(std::string text, std::string name) {
  auto source = std::make_unique<Source>();
  source->text = std::move(text);
  return CarmenLogReader(std::move(source), std::move(name));
}

// Reads the next whole line into line_; an over-long line is consumed, counted, skipped.
bool CarmenLogReader::NextLine() {
  while (true) {
    line_.clear();
    bool complete = false;
    bool too_long = false;
    if (!source_->Read(line_, complete, read_error_)) return false;
    while (!complete) {
      if (line_.size() > kMaxCarmenLineBytes) {
        too_long = true;
        line_.clear();
      }
      if (!source_->Read(line_, complete, read_error_)) break;
    }
    ++stats_.lines;
    if (!too_long && line_.size() <= kMaxCarmenLineBytes) return true;
    CountMalformed("line longer than " + std::to_string(kMaxCarmenLineBytes) + " bytes");
  }
}

void CarmenLogReader::CountMalformed(std::string reason) {
  ++stats_.malformed;
  if (stats_.first_malformed.size() < kMaxRecordedCarmenErrors) {
    stats_.first_malformed.push_back({stats_.lines, std::move(reason)});
  }
}

bool CarmenLogReader::Next(LaserScan& scan) {
  while (NextLine()) {
    switch (ClassifyCarmenLine(line_)) {
      case CarmenLineKind::kOdometry: ++stats_.odometry; continue;
      case CarmenLineKind::kOther: ++stats_.other; continue;
      case CarmenLineKind::kFlaser:
      case CarmenLineKind::kRobotLaser1: break;
    }
    if (Status parsed = ParseCarmenLaserLine(line_, scan); !parsed) {
      CountMalformed(parsed.error().message);
      continue;
    }
    ++(scan.message == CarmenMessage::kFlaser ? stats_.flaser : stats_.robotlaser);
    return true;
  }
  return false;
}

Result<CarmenScans> ReadCarmenLaserScans(const std::filesystem::path& path) {
  Result<CarmenLogReader> reader = CarmenLogReader::Open(path);
  if (!reader) return reader.error();
  CarmenScans out;
  LaserScan scan;
  while (reader->Next(scan)) out.scans.push_back(scan);
  if (!reader->read_error().empty()) {
    return MakeError("reading " + path.string() + ": " + reader->read_error());
  }
  out.stats = reader->stats();
  return out;
}

}  // namespace flat2d::hal::carmen
