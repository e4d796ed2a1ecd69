// A KITTI odometry sequence directory (Geiger et al. 2012, devkit readme): velodyne/
// holding one scan a frame (NNNNNN.bin, kitti_bin_file.hpp), and times.txt, one line a
// frame, the frame's time in seconds from the sequence's start. The scans are taken in
// the order of their names; the first times.txt lines give their stamps (a directory cut
// from a longer sequence may keep the whole times.txt).
//
// Errors name the file: no velodyne/ directory or no .bin in it, no times.txt, a line that
// is not a number (with its line number), fewer times than scans, or times that do not
// increase.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::cloud {

struct KittiSequence {
  std::vector<std::filesystem::path> scans;  // velodyne/*.bin in frame order
  std::vector<TimeNs> stamps;                // per scan, from times.txt
};

// Whether `path` is a directory with a velodyne/ subdirectory: what a tool taking either a
// capture file or a sequence looks for.
bool IsKittiSequence(const std::filesystem::path& path);

Result<KittiSequence> OpenKittiSequence(const std::filesystem::path& directory);

// times.txt's text as stamps; `source_name` starts error messages.
Result<std::vector<TimeNs>> ParseKittiTimes(std::string_view text, std::string_view source_name);

}  // namespace flat2d::hal::cloud
