// Prior map files: a class grid (cell_class.hpp) cut into square tiles, each compressed
// independently with zstd, behind a protobuf header (prior_map.proto) that says what the
// map is, where it is on Earth and where each tile is (DESIGN.md "Prior map file").
//
// Layout, little-endian:
//   bytes 0-7    magic "FLAT2DMP"
//   bytes 8-11   format version (kPriorMapFormatVersion)
//   bytes 12-15  header length H
//   bytes 16-19  CRC-32 of the header bytes
//   bytes 20..   the PriorMapHeader, H bytes
//   then         the tile section: each tile's zstd frame, tile_cells^2 cell bytes row-major
//                (row 0 = lowest y), at the offset its TileEntry gives, with its CRC-32.
//                then each viewpoint's zstd frame (its Viewpoint entry gives offset and CRC-32).
// Tiles whose cells are all unknown are not stored. A map can be written from a ClassGrid or
// from a TileSource that produces one tile at a time, so maps larger than memory can be
// written (a city, the 1 km^2 reader test).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/prior_map/prior_map.pb.h"

namespace flat2d::maps {

inline constexpr char kPriorMapMagic[8] = {'F', 'L', 'A', 'T', '2', 'D', 'M', 'P'};
inline constexpr std::uint32_t kPriorMapFormatVersion = 1;
inline constexpr std::size_t kPriorMapPreambleBytes = 20;
inline constexpr int kMaxTileCells = 1024;             // 1 MB a tile at most
inline constexpr std::uint32_t kMaxHeaderBytes = 64u << 20;  // a 64 MB index: millions of tiles
inline constexpr int kMaxViewpointSideCells = 4096;         // 204.8 m at 5 cm

struct PriorMapWriteOptions {
  int tile_cells = 256;     // 12.8 m at 5 cm
  int zstd_level = 19;      // offline: small files matter more than seconds
  Georeference georeference;
  std::string created_by = "flat2d";
  std::string created_utc;  // empty: now
  std::string source;
};

// Where a map's cells come from when writing: its extent, and one tile at a time.
class TileSource {
 public:
  virtual ~TileSource() = default;
  virtual const GridGeometry& geometry() const = 0;
  // Fills `cells` (tile_cells^2, row-major) with tile (col, row), unknown beyond the map;
  // false when every cell is unknown (the tile is not stored).
  virtual bool FillTile(int tile_cells, int col, int row, std::span<std::uint8_t> cells) = 0;
};

// A viewpoint sub-map to store: the historic pose and the visible cells, a grid at the
// map's resolution whose cells line up with the map's (viewpoint.hpp builds them).
struct ViewpointGrid {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double time_s = 0.0;
  ClassGrid cells;
};

// Writes `grid` (its origin and resolution become the map's) as a prior map file.
Status WritePriorMap(const ClassGrid& grid, const std::filesystem::path& path, const PriorMapWriteOptions& options,
                     std::span<const ViewpointGrid> viewpoints = {});
Status WritePriorMap(TileSource& source, const std::filesystem::path& path, const PriorMapWriteOptions& options,
                     std::span<const ViewpointGrid> viewpoints = {});

}  // namespace flat2d::maps
