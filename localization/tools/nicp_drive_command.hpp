// `flat2d-map build --mode nicp DRIVE --out DIR`: a Velodyne drive tracked by NICP
// (nicp_drive_build.hpp) and its outputs written.
#pragma once

namespace flat2d::localization::tools {

// argv holds the build arguments (including --mode nicp). Exit status: 0 built, 1 usage,
// 2 a file cannot be read or written, 3 nothing to map.
int NicpDriveCommand(int argc, char** argv);

// True when the build's positional argument is a Velodyne capture (.pcap, .pcapng).
bool IsDriveBuild(int argc, char** argv);

extern const char* const kNicpDriveUsage;

}  // namespace flat2d::localization::tools
