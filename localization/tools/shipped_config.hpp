// Where the shipped configuration files are for the offline tools: the installed copy
// (CMAKE_INSTALL_DATADIR/flat2d/config) when it exists, else the source tree's packaging/.
#pragma once

#include <string>

namespace flat2d::localization {

// The structure-grid options flat2d-grid and flat2d-map use without --config.
std::string ShippedGridConfig();

// The 3D feature extraction options `flat2d-map features` uses without --features-config.
std::string ShippedFeaturesConfig();

// The simulator vehicle's odometry model (flat2d-sim's drives).
std::string ShippedSimOdometryConfig();

}  // namespace flat2d::localization
