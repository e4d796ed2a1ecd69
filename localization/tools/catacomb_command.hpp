// `flat2d-map build --mode catacomb DRIVE --out DIR`: local-map 3D SLAM of a Velodyne drive
// (catacomb_build.hpp) and its outputs written.
#pragma once

namespace flat2d::localization::tools {

// argv holds the build arguments (including --mode catacomb). Exit status: 0 built, 1
// usage, 2 a file cannot be read or written, 3 nothing to map.
int CatacombCommand(int argc, char** argv);

extern const char* const kCatacombUsage;

}  // namespace flat2d::localization::tools
