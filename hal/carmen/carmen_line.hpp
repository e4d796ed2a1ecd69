// Parsing one line of a CARMEN log (see carmen_log.hpp for the message layouts).
#pragma once

#include <string_view>

#include "hal/carmen/carmen_log.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::carmen {

enum class CarmenLineKind { kFlaser, kRobotLaser1, kOdometry, kOther };

// What the line's first word says it is.
CarmenLineKind ClassifyCarmenLine(std::string_view line);

// Parses a FLASER or ROBOTLASER1 line into `scan` (its ranges vector is reused); the error
// names the field that failed.
Status ParseCarmenLaserLine(std::string_view line, LaserScan& scan);

}  // namespace flat2d::hal::carmen
