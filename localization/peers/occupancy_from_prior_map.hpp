// The prior map as MRPT's occupancy grid, for the Monte-Carlo localization peer (issue 9):
// the same map flat2d localizes against, seen the way a 2D laser localizer sees a map.
//
// A cell of the occupancy grid is occupied when any slammable prior-map cell falls in it
// (the structure the scans are made of), free when the map saw ground or hazard there and
// no structure, and unknown (0.5) where the map has no data. MRPT stores the probability of
// being free: 0 is certainly occupied.
#pragma once

#include <mrpt/maps/COccupancyGridMap2D.h>

#include "hal/common/error.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::localization::peers {

struct OccupancyStats {
  std::size_t occupied = 0;
  std::size_t free = 0;
  std::size_t cells = 0;
};

// The map's stored extent at `resolution_m` (a multiple of the map's is best: the cells then
// share borders). An error when the map is empty or a tile cannot be read.
Result<mrpt::maps::COccupancyGridMap2D::Ptr> OccupancyFromPriorMap(maps::PriorMapReader& map, double resolution_m,
                                                                  OccupancyStats* stats = nullptr);

}  // namespace flat2d::localization::peers
