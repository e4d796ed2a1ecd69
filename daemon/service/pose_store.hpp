// The last good pose on disk (persisted_pose.proto), written atomically: a temporary file
// in the same folder, fsync, rename over the old one, fsync the folder. A crash at any
// point leaves either the old file or the new one, never a torn one.
#pragma once

#include <filesystem>

#include "daemon/service/persisted_pose.pb.h"
#include "hal/common/error.hpp"

namespace flat2d::daemon {

Status SavePersistedPose(const std::filesystem::path& path, const PersistedPose& pose);
// An error when the file is missing, unreadable or invalid (the caller falls back).
Result<PersistedPose> LoadPersistedPose(const std::filesystem::path& path);

}  // namespace flat2d::daemon
