// `flat2d-map build --mode landmarks DRIVE --out DIR`: landmark SLAM over a drive (issue 13).
#pragma once

namespace flat2d::localization::tools {

// argv holds every argument after "build". Exit status: 0 built, 1 usage, 2 a file cannot be
// read, is invalid or cannot be written, 3 nothing gridded for the map.
int LandmarkDriveCommand(int argc, char** argv);

extern const char* const kLandmarkDriveUsage;

}  // namespace flat2d::localization::tools
