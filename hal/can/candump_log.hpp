// Reading and writing candump -l log files (can-utils), the field's format for CAN logs.
//
// CandumpReader is a CanFrameSource over a log file, or over a log held in memory (tests,
// fuzzing). Steps: (1) read the file in fixed 64 KiB blocks and cut it into lines, so a
// log of any size needs no more memory and a line longer than kMaxCandumpLineBytes (a
// damaged or binary file) is skipped, not buffered; (2) parse each line with
// ParseCandumpLine (candump_line.hpp); (3) count what each line was, and for malformed
// lines keep the first kMaxRecordedMalformedLines line numbers and reasons, so that a bad
// line is reported and skipped, never fatal; (4) return the frames in file order with the
// log's own times (Unix time, or seconds since boot for some loggers). CandumpWriter
// writes frames in exactly candump -l's format, so that reading a candump log and writing
// it again reproduces it byte for byte.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hal/can/can_frame.hpp"
#include "hal/can/candump_line.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

inline constexpr std::size_t kMaxRecordedMalformedLines = 16;
inline constexpr std::size_t kMaxCountedInterfaces = 8;

struct CandumpMalformedLine {
  std::uint64_t line = 0;  // 1-based line number
  CandumpError error = CandumpError::kNone;
};

struct CandumpInterfaceFrames {
  std::string name;  // <= 15 characters: kept in the string's inline buffer, no allocation
  std::uint64_t frames = 0;
};

struct CandumpReaderStats {
  std::uint64_t lines = 0;            // every line read, good or not
  std::uint64_t frames = 0;           // frames returned
  std::uint64_t error_frames = 0;     // of them, error frames (CAN_ERR_FLAG)
  std::uint64_t remote_frames = 0;    // of them, remote frames
  std::uint64_t fd_frames = 0;        // of them, CAN FD frames
  std::uint64_t transmitted = 0;      // of them, marked T (sent by the logging host)
  std::uint64_t ignored_lines = 0;    // blank lines and '#' comments
  std::uint64_t drop_notices = 0;     // candump "DROPCOUNT:" lines
  std::uint64_t malformed = 0;        // total malformed lines
  std::vector<CandumpMalformedLine> first_malformed;  // the first kMaxRecordedMalformedLines
  // Frames per interface for the first kMaxCountedInterfaces names seen, the rest summed.
  std::vector<CandumpInterfaceFrames> interfaces;
  std::uint64_t other_interface_frames = 0;
  std::string read_error;  // set when reading the file failed part-way

  // Frames seen on `name` (0 if it was not among the counted interfaces).
  std::uint64_t FramesOn(std::string_view name) const;
};

class CandumpReader final : public CanFrameSource {
 public:
  static Result<CandumpReader> Open(const std::filesystem::path& path);
  // Reads a log held in memory (tests, fuzzing); the text is moved in, not copied.
  static CandumpReader FromString(std::string text, std::string name = "in-memory log");

  CandumpReader(CandumpReader&&) noexcept = default;
  CandumpReader& operator=(CandumpReader&&) noexcept = default;
  ~CandumpReader() override = default;

  // The next frame; false at the end of the log. Allocates nothing.
  bool Next(CanFrame& frame) override;

  // The direction marker of the frame Next returned last (candump -x), if it had one.
  CandumpDirection last_direction() const { return last_direction_; }
  const CandumpReaderStats& stats() const { return stats_; }
  const std::string& name() const { return name_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  CandumpReader(std::unique_ptr<std::FILE, FileCloser> file, std::string buffer,
                bool end_of_input, std::string name);
  bool NextLine(std::string_view& line, bool& too_long);
  void Refill();
  void CountMalformed(CandumpError error);
  void CountFrame(const CanFrame& frame, CandumpDirection direction);

  std::unique_ptr<std::FILE, FileCloser> file_;  // null for in-memory logs
  // A window onto the file (or the whole in-memory log): [begin_, end_) is unread.
  std::string buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool end_of_input_ = false;
  bool skipping_long_line_ = false;  // inside a line that outgrew the window
  std::string name_;
  CandumpDirection last_direction_ = CandumpDirection::kUnknown;
  CandumpReaderStats stats_;
};

struct CandumpWriterOptions {
  // candump -l's own format; seconds_digits = 0 writes unpadded seconds as some
  // converters do (e.g. the DERIVED comma2k19 logs), interface_width pads names.
  int seconds_digits = 10;
  int interface_width = 0;
  std::string fallback_interface = "can0";  // for frames without an interface name
};

class CandumpWriter {
 public:
  static Result<CandumpWriter> Open(const std::filesystem::path& path,
                                    CandumpWriterOptions options = {});

  CandumpWriter(CandumpWriter&&) noexcept = default;
  CandumpWriter& operator=(CandumpWriter&&) noexcept = default;
  ~CandumpWriter() = default;  // closes the file; call Close() to learn of write errors

  // Appends one line. Frames that candump could not have written (negative times,
  // ids or lengths out of range) are refused with the reason; the file is unchanged.
  Status Write(const CanFrame& frame, CandumpDirection direction = CandumpDirection::kUnknown);
  // Flushes and closes; reports a failed write (e.g. a full disk). Idempotent.
  Status Close();

  std::uint64_t frames_written() const { return frames_written_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  CandumpWriter(std::unique_ptr<std::FILE, FileCloser> file, CandumpWriterOptions options,
                std::string path);

  std::unique_ptr<std::FILE, FileCloser> file_;
  CandumpWriterOptions options_;
  std::string path_;
  std::uint64_t frames_written_ = 0;
};

}  // namespace flat2d::hal::can
