// `flat2d-map build --mode nicp DRIVE --out DIR`: a Velodyne drive tracked by NICP
// (nicp_drive_build.hpp) and its outputs written.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "localization/tools/nicp_drive_build.hpp"

namespace flat2d::localization::tools {

// argv holds the build arguments (including --mode nicp). Exit status: 0 built, 1 usage,
// 2 a file cannot be read or written, 3 nothing to map.
int NicpDriveCommand(int argc, char** argv);

// True when the build's positional argument is a Velodyne capture (.pcap, .pcapng).
bool IsDriveBuild(int argc, char** argv);

extern const char* const kNicpDriveUsage;

// The arguments `build --mode nicp DRIVE` shares with `--mode catacomb`.
struct NicpDriveArgs {
  std::string out;
  std::optional<std::string> config, anchor;
  NicpDriveOptions options;
  bool json = false;
};

// Parses the shared flag (or the capture) at argv[i], advancing i past its value; false
// when argv[i] is none of them. Exits with status 1 on a bad value.
bool ParseNicpDriveFlag(int argc, char** argv, int& i, NicpDriveArgs& a);
// Exits with status 1 unless DRIVE and --out are given and the CAN flags go together.
void CheckNicpDriveArgs(const NicpDriveArgs& a, const std::string& mode, const char* usage);
// The length of a trajectory's path (m).
double PathLength(const std::vector<hal::trajectory::StampedPose>& trajectory);
// Loads the grid configuration and the anchor track; exits with status 2 when one cannot be read.
void PrepareNicpDrive(NicpDriveArgs& a);

}  // namespace flat2d::localization::tools
