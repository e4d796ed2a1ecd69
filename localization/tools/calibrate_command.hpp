// `flat2d-map calibrate DRIVE [DRIVE2]`: the LiDAR's mounting on the vehicle from a drive,
// and the second LiDAR's relative to the first from a second recording of the same drive
// (issue 12, item 7; calibrate_run.hpp).
#pragma once

namespace flat2d::localization::tools {

// argv holds the arguments after "calibrate". Exit status: 0 done, 1 usage, 2 an input
// cannot be read, 3 the calibration failed (too little motion, no registration).
int CalibrateCommand(int argc, char** argv);

extern const char* const kCalibrateUsage;

}  // namespace flat2d::localization::tools
