// The GNSS fixes a Velodyne sensor echoes in its position packets ($GPRMC, nmea.hpp), read
// from a capture as a track for the map builder's scale (`flat2d-map build
// --scale-from-gnss`). Positions are east/north metres in the tangent plane at the first
// fix; only the track's shape matters to a scale fit, not where its frame is.
#pragma once

#include <filesystem>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/evaluation/relations.hpp"

namespace flat2d::localization {

struct GnssTrackStats {
  std::uint64_t position_packets = 0;
  std::uint64_t malformed = 0;  // position packets that did not decode
  std::uint64_t void_fixes = 0;  // RMC without a valid position (status V, mode N)
};

// One pose per distinct valid fix, at the fix's UTC time, heading 0. An error when the
// capture cannot be read.
Result<std::vector<evaluation::TimedPose>> ReadGnssTrack(const std::filesystem::path& capture,
                                                         GnssTrackStats* stats = nullptr);

}  // namespace flat2d::localization
