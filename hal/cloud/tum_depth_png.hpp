// Reading depth images of the TUM RGB-D benchmark (Sturm et al., IROS 2012) and the
// lists that name them.
//
// A depth frame is a 16-bit grey PNG (decoded with libpng), each value the depth times
// depth_scale (5000 for TUM's Kinect data: 1 = 0.2 mm), 0 where the sensor saw nothing.
// Any other PNG (8-bit, colour, palette) is an error naming the file and what it holds,
// not a silent conversion: a scaled 8-bit image would pass as depth of a few centimetres.
// The list (TUM's depth.txt) has '#' comments and lines "timestamp filename", the file
// relative to the list's folder.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

// Largest width or height accepted: bounds the allocation a corrupt header can ask for.
inline constexpr int kMaxDepthImageSide = 16384;

struct DepthFrame {
  double time_s = 0.0;           // the list's timestamp, seconds
  std::filesystem::path file;    // the PNG, resolved against the list's folder
};

Result<DepthImage> ReadTumDepthPng(const std::filesystem::path& path, double depth_scale = 5000.0);

Result<std::vector<DepthFrame>> ReadTumAssociationList(const std::filesystem::path& path);
// The same for text in memory: `source_name` starts error messages, relative file names
// are resolved against `folder`.
Result<std::vector<DepthFrame>> ParseTumAssociationList(std::string_view text, std::string_view source_name,
                                                        const std::filesystem::path& folder);

}  // namespace flat2d::hal::cloud
