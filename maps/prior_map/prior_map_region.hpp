// A region of a prior map as one class grid, for rendering and comparison (`flat2d-map
// render`): the cells of every tile it overlaps, read through the reader's cache, so a
// region of any map is read in the memory of the region plus the cache.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::maps {

struct MapRegion {
  Eigen::Vector2d low;   // map frame, metres
  Eigen::Vector2d high;
};

// The map's stored tiles' extent (all of the map that is not unknown).
std::optional<MapRegion> StoredExtent(const PriorMapReader& reader);

// The cells within `region` (clipped to the map), aligned with the map's cells; an error
// when the region misses the map, is larger than max_cells, or a tile is damaged.
Result<ClassGrid> ReadRegion(PriorMapReader& reader, const MapRegion& region, std::size_t max_cells = 400'000'000);

}  // namespace flat2d::maps
