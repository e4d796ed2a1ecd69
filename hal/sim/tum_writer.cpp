#include "hal/sim/tum_writer.hpp"

#include <array>
#include <cerrno>
#include <cinttypes>
#include <cstring>

namespace flat2d::hal::sim {
namespace {

// Room for "t x y z qx qy qz qw": 8 numbers of at most ~30 characters each.
constexpr std::size_t kMaxLineBytes = 320;

// Writes the line (without newline) into `buffer`; returns its length, or 0 if invalid.
std::size_t FormatInto(std::array<char, kMaxLineBytes>& buffer, TimeNs time_ns,
                       const Eigen::Isometry3d& world_T_body) {
  if (time_ns < 0) return 0;
  Eigen::Quaterniond q(world_T_body.rotation());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // one sign per rotation: equal bytes
  const Eigen::Vector3d& p = world_T_body.translation();
  if (!p.allFinite() || !q.coeffs().allFinite()) return 0;
  const int length = std::snprintf(
      buffer.data(), buffer.size(), "%" PRId64 ".%09" PRId64 " %.9f %.9f %.9f %.9f %.9f %.9f %.9f",
      time_ns / kNsPerSecond, time_ns % kNsPerSecond, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(),
      q.w());
  if (length <= 0 || static_cast<std::size_t>(length) >= buffer.size()) return 0;
  return static_cast<std::size_t>(length);
}

}  // namespace

Result<TumWriter> TumWriter::Open(const std::filesystem::path& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) return MakeError(path.string() + ": cannot write: " + std::strerror(errno));
  return TumWriter(std::move(file), path.string());
}

Status TumWriter::Write(TimeNs time_ns, const Eigen::Isometry3d& world_T_body) {
  if (!file_) return MakeError(path_ + ": write after close");
  std::array<char, kMaxLineBytes> line{};
  const std::size_t length = FormatInto(line, time_ns, world_T_body);
  if (length == 0) return MakeError(path_ + ": pose not writable (negative time or non-finite)");
  line[length] = '\n';
  if (std::fwrite(line.data(), 1, length + 1, file_.get()) != length + 1) {
    return MakeError(path_ + ": write failed: " + std::strerror(errno));
  }
  ++poses_written_;
  return Status::Ok();
}

Status TumWriter::Close() {
  if (!file_) return Status::Ok();
  const bool flushed = std::fflush(file_.get()) == 0;
  const bool closed = std::fclose(file_.release()) == 0;
  if (!flushed || !closed) return MakeError(path_ + ": write failed: " + std::strerror(errno));
  return Status::Ok();
}

std::string FormatTumLine(TimeNs time_ns, const Eigen::Isometry3d& world_T_body) {
  std::array<char, kMaxLineBytes> line{};
  return std::string(line.data(), FormatInto(line, time_ns, world_T_body));
}

}  // namespace flat2d::hal::sim
