// Writing a trajectory in the TUM RGB-D benchmark format, the field's plain-text format
// for ground truth and estimates (Sturm et al. 2012): one line "t x y z qx qy qz qw" per
// pose, t in seconds.
//
// The simulator's truth must be byte-identical between runs and exact enough to judge
// centimetre-level estimates, so every number is written with fixed decimals: t from the
// integer nanoseconds (seconds.nnnnnnnnn, no floating-point rounding), positions and the
// unit quaternion with 9 decimals. The quaternion is normalized and its sign chosen with
// qw >= 0, so equal rotations always print equally. Writing allocates nothing.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::sim {

class TumWriter {
 public:
  // Creates (or replaces) the file; errors name the path.
  static Result<TumWriter> Open(const std::filesystem::path& path);

  TumWriter(TumWriter&&) noexcept = default;
  TumWriter& operator=(TumWriter&&) noexcept = default;
  ~TumWriter() = default;  // closes the file; call Close() to learn of write errors

  // Appends one line for world_T_body at absolute time `time_ns` (must be >= 0).
  Status Write(TimeNs time_ns, const Eigen::Isometry3d& world_T_body);
  // Flushes and closes; reports a failed write (e.g. a full disk). Idempotent.
  Status Close();

  std::uint64_t poses_written() const { return poses_written_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  TumWriter(std::unique_ptr<std::FILE, FileCloser> file, std::string path)
      : file_(std::move(file)), path_(std::move(path)) {}

  std::unique_ptr<std::FILE, FileCloser> file_;
  std::string path_;
  std::uint64_t poses_written_ = 0;
};

// One TUM line without the newline, as TumWriter writes it (for tests and other writers).
std::string FormatTumLine(TimeNs time_ns, const Eigen::Isometry3d& world_T_body);

}  // namespace flat2d::hal::sim
