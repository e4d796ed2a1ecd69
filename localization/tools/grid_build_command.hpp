// `flat2d-map build --carmen LOG | --pcap CAPTURE ...`: the offline 2D SLAM of thesis
// chapters 3 and 7.3 (localization/mapping) into a prior map file, with its trajectories,
// preview and JSON summary. Exit status: 1 usage, 2 a file cannot be read or written, 3
// nothing to map.
#pragma once

namespace flat2d::localization::tools {

extern const char* const kGridBuildUsage;

// argv without the "build" command word.
int GridBuildCommand(int argc, char** argv);

}  // namespace flat2d::localization::tools
