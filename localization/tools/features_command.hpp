// `flat2d-map features INPUT`: 3D line and plane features of LiDAR revolutions (issue 13).
#pragma once

namespace flat2d::localization::tools {

// argv holds the arguments after "features". Exit status: 0 done, 1 usage or options,
// 2 an input, configuration or truth file cannot be read or is invalid.
int FeaturesCommand(int argc, char** argv);

extern const char* const kFeaturesUsage;

}  // namespace flat2d::localization::tools
