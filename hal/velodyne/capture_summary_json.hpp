// The capture summary as one JSON object: the machine-readable output of
// `flat2d-inspect --json`. Keys are an interface scripts rely on: product,
// return_mode, data_packets, position_packets, revolutions, points, malformed are
// always present; more keys may be added, none renamed.
#pragma once

#include <string>

#include "hal/velodyne/capture_summary.hpp"

namespace flat2d::hal::velodyne {

std::string CaptureSummaryToJson(const CaptureSummary& summary, const std::string& capture_path);

}  // namespace flat2d::hal::velodyne
