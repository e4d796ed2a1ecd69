// Reading prior map files (prior_map_file.hpp) in fixed memory: the header and tile index
// are read and checked at Open; tiles are read, checked (CRC-32, zstd frame, size, cell
// values) and decompressed on demand into at most `cache_tiles` preallocated slots, the
// least recently used one giving way. So a city-sized map runs in the memory of its index
// plus cache_tiles x tile_cells^2 bytes, whatever its size on disk.
//
// A damaged file is an error that names what is wrong (the preamble, a header field, or
// the tile and how), never a crash; a damaged tile is not cached, and ClassAt answers
// unknown there and counts it. After Open nothing allocates.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/prior_map/prior_map_file.hpp"

namespace flat2d::maps {

// Where a reader's bytes come from: a file read with pread, or bytes in memory.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual std::uint64_t size() const = 0;
  // Reads exactly out.size() bytes at `offset`; false if there are fewer or reading fails.
  virtual bool Read(std::uint64_t offset, std::span<std::uint8_t> out) = 0;
};

struct PriorMapReaderStats {
  std::uint64_t tile_reads = 0;    // tiles read from the file (cache misses)
  std::uint64_t cache_hits = 0;
  std::uint64_t evictions = 0;
  std::uint64_t damaged_tiles = 0;  // reads that failed a check
};

class PriorMapReader {
 public:
  static Result<PriorMapReader> Open(const std::filesystem::path& path, int cache_tiles = 16);
  // The same over a file's bytes in memory (tests, fuzzing); `name` starts error messages.
  static Result<PriorMapReader> FromBytes(std::vector<std::uint8_t> bytes, int cache_tiles, std::string name);

  PriorMapReader(PriorMapReader&&) noexcept;
  PriorMapReader& operator=(PriorMapReader&&) noexcept;
  ~PriorMapReader();

  const PriorMapHeader& header() const { return header_; }
  // The whole map as one grid's geometry (width_tiles x tile_cells columns, ...).
  GridGeometry geometry() const;
  std::uint64_t file_bytes() const { return file_bytes_; }

  // Tile (col, row)'s cells, tile_cells^2 bytes row-major; a tile the file does not store is
  // all unknown. Valid until the next call that loads a tile.
  Result<std::span<const std::uint8_t>> Tile(int col, int row);
  // The class at a map-frame point: unknown outside the map or on a damaged tile.
  CellClass ClassAt(const Eigen::Vector2d& point);

  // Viewpoint sub-maps (prior_map.proto's Viewpoint): header().viewpoints(i) says where
  // viewpoint i is; ViewpointCells reads and checks its cells (width x height, row-major)
  // into one buffer sized at Open for the largest. Valid until the next call.
  int viewpoint_count() const { return header_.viewpoints_size(); }
  Result<std::span<const std::uint8_t>> ViewpointCells(int index);
  // Viewpoint i's cells as a grid in the map frame (allocates: tools and tests).
  Result<ClassGrid> ViewpointGrid(int index);

  const PriorMapReaderStats& stats() const { return stats_; }
  int cache_tiles() const { return static_cast<int>(slots_.size()); }

 private:
  struct Slot {
    int entry = -1;            // index into header_.tiles(); -1 = empty
    std::uint64_t last_used = 0;
    std::vector<std::uint8_t> cells;
  };
  PriorMapReader() = default;
  static Result<PriorMapReader> Finish(std::unique_ptr<ByteSource> source, int cache_tiles, const std::string& name);
  Status CheckIndex();
  Status CheckViewpoints();
  // Reads the `bytes`-long zstd frame at `offset` into `out`, which it must fill exactly.
  Status Decompress(std::uint64_t offset, std::uint32_t bytes, std::uint32_t crc, std::span<std::uint8_t> out,
                    const std::string& what);
  Status LoadInto(int entry, Slot& slot);

  std::string name_;
  std::unique_ptr<ByteSource> source_;
  PriorMapHeader header_;
  std::uint64_t file_bytes_ = 0;
  std::uint64_t tile_section_ = 0;      // file offset of the tile section
  std::vector<std::int32_t> entry_of_;  // tile col + row * width_tiles -> entry, -1 absent
  std::vector<Slot> slots_;
  std::vector<std::uint8_t> compressed_;  // the largest tile's or viewpoint's compressed bytes
  std::vector<std::uint8_t> viewpoint_cells_;  // the largest viewpoint's cells
  std::vector<std::uint8_t> unknown_;     // an absent tile
  struct ZstdContext;
  std::unique_ptr<ZstdContext> zstd_;
  std::uint64_t clock_ = 0;
  PriorMapReaderStats stats_;
};

}  // namespace flat2d::maps
