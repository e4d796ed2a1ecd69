// `flat2d-map build --mode nicp depth.txt --out DIR`: a depth sequence tracked by NICP.
#pragma once

namespace flat2d::localization::tools {

// argv holds the build arguments (including --mode nicp). Exit status: 0 built, 1 usage,
// 2 a file cannot be read or written.
int NicpBuildCommand(int argc, char** argv);

extern const char* const kNicpBuildUsage;

}  // namespace flat2d::localization::tools
