// What a prior map file holds, as `flat2d-map info` prints it: tiles, mapped area, file
// bytes (and bytes per 1000 m^2 mapped, the compactness figure), resolution, georeference,
// viewpoints and how it was made. Read from the header alone: no tile is decompressed.
#pragma once

#include <cstdint>
#include <string>

#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::maps {

struct PriorMapSummary {
  std::uint64_t file_bytes = 0;
  std::uint64_t tile_bytes = 0;       // compressed tiles (the global mosaic)
  std::uint64_t viewpoint_bytes = 0;  // compressed viewpoint sub-maps
  int tiles = 0;
  int tile_cells = 0;
  int width_tiles = 0;
  int height_tiles = 0;
  double resolution_m = 0.0;
  double mapped_area_m2 = 0.0;        // cells not unknown
  double slammable_area_m2 = 0.0;
  double extent_x_m = 0.0;            // of the tile grid
  double extent_y_m = 0.0;
  int viewpoints = 0;
  std::string georeference;           // "none", "ENU lat,lon,alt", "UTM 32N +e +n"
  std::string created_by, created_utc, source;

  // File bytes per 1000 m^2 mapped, and the mosaic's (tiles only) alone.
  double BytesPer1000m2() const { return mapped_area_m2 > 0 ? file_bytes * 1000.0 / mapped_area_m2 : 0.0; }
  double TileBytesPer1000m2() const { return mapped_area_m2 > 0 ? tile_bytes * 1000.0 / mapped_area_m2 : 0.0; }
};

PriorMapSummary SummarizePriorMap(const PriorMapReader& reader);
std::string SummaryText(const PriorMapSummary& summary);
std::string SummaryJson(const PriorMapSummary& summary);

}  // namespace flat2d::maps
