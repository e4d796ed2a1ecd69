#include "daemon/service/pose_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <string>

#include <google/protobuf/text_format.h>

#include "hal/config/text_proto.hpp"
#include "hal/net/socket_fd.hpp"

namespace flat2d::daemon {
namespace {

Error FileError(const std::filesystem::path& path, const std::string& what) {
  return MakeError(path.string() + ": " + what + ": " + hal::net::ErrnoText(errno));
}

bool WriteAll(int fd, const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    written += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

Status SavePersistedPose(const std::filesystem::path& path, const PersistedPose& pose) {
  std::string text;
  if (!google::protobuf::TextFormat::PrintToString(pose, &text)) return MakeError("cannot format the persisted pose");
  const std::filesystem::path temporary = path.string() + ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return FileError(temporary, "open");
  const bool written = WriteAll(fd, text) && ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  if (!written) {
    errno = saved_errno;
    return FileError(temporary, "write");
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) return FileError(path, "rename");
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  const int folder_fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder_fd >= 0) {
    ::fsync(folder_fd);
    ::close(folder_fd);
  }
  return Status::Ok();
}

Result<PersistedPose> LoadPersistedPose(const std::filesystem::path& path) {
  PersistedPose pose;
  if (Status loaded = hal::config::LoadTextProto(path, pose); !loaded.ok()) return loaded.error();
  if (!std::isfinite(pose.x()) || !std::isfinite(pose.y()) || !std::isfinite(pose.theta())) {
    return MakeError(path.string() + ": the pose is not finite");
  }
  return pose;
}

}  // namespace flat2d::daemon
