// `flat2d-map register SOURCE TARGET`: NICP between two range files (issue 11).
#pragma once

namespace flat2d::localization::tools {

// argv holds the arguments after "register". Exit status: 0 registered, 1 usage, 2 a file
// cannot be read or is invalid, 3 registration failed (the result is still printed).
int RegisterCommand(int argc, char** argv);

extern const char* const kRegisterUsage;

}  // namespace flat2d::localization::tools
