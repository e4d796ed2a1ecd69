// libFuzzer target: arbitrary bytes as a prior map file into PriorMapReader, then every
// listed tile (at most 64) read through a 4-tile cache, a few ClassAt queries, and every
// viewpoint sub-map (at most 16).
//
// Maps are copied between machines and disks; a damaged or hostile file must end in an
// Error naming what is wrong, never a crash, a hang or undefined behaviour. A random file
// rarely passes the magic and the CRCs, so the first byte picks what the fuzzer controls:
//   0: the whole file, as is;
//   1: the header (4 bytes of length, then its bytes) and the tile section; the preamble
//      and header CRC are made right, so parsing and index checks are explored;
//   2: as 1, and every tile's and viewpoint's CRC is made right too, so zstd frames and
//      their contents are.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <google/protobuf/stubs/logging.h>

#include "maps/prior_map/prior_map_reader.hpp"

namespace {

using namespace flat2d::maps;

void PutLittleEndian(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint32_t Crc(const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32(0L, data, static_cast<uInt>(size)));
}

// Mode 1 and 2: a well-formed preamble around the fuzzer's header and tiles.
std::vector<std::uint8_t> Wrap(const std::uint8_t* data, std::size_t size, bool fix_tiles) {
  std::uint32_t length = 0;
  if (size >= 4) std::memcpy(&length, data, 4), data += 4, size -= 4;
  length = static_cast<std::uint32_t>(std::min<std::size_t>(length, size));
  std::string header(reinterpret_cast<const char*>(data), length);
  const std::uint8_t* tiles = data + length;
  const std::size_t tile_bytes = size - length;
  if (fix_tiles) {
    PriorMapHeader parsed;
    if (parsed.ParseFromString(header)) {
      for (TileEntry& tile : *parsed.mutable_tiles()) {
        if (tile.offset() <= tile_bytes && tile.compressed_bytes() <= tile_bytes - tile.offset()) {
          tile.set_crc32(Crc(tiles + tile.offset(), tile.compressed_bytes()));
        }
      }
      for (Viewpoint& viewpoint : *parsed.mutable_viewpoints()) {
        if (viewpoint.offset() <= tile_bytes && viewpoint.compressed_bytes() <= tile_bytes - viewpoint.offset()) {
          viewpoint.set_crc32(Crc(tiles + viewpoint.offset(), viewpoint.compressed_bytes()));
        }
      }
      header = parsed.SerializeAsString();
    }
  }
  std::vector<std::uint8_t> file(kPriorMapMagic, kPriorMapMagic + sizeof(kPriorMapMagic));
  PutLittleEndian(file, kPriorMapFormatVersion);
  PutLittleEndian(file, static_cast<std::uint32_t>(header.size()));
  PutLittleEndian(file, Crc(reinterpret_cast<const std::uint8_t*>(header.data()), header.size()));
  file.insert(file.end(), header.begin(), header.end());
  file.insert(file.end(), tiles, tiles + tile_bytes);
  return file;
}

}  // namespace

// protobuf logs a line for each header string that is not UTF-8; the reader's own error
// says the header does not parse, and the fuzzer's log should show findings only.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0] % 3;
  std::vector<std::uint8_t> file = mode == 0 ? std::vector<std::uint8_t>(data + 1, data + size)
                                             : Wrap(data + 1, size - 1, mode == 2);
  auto reader = PriorMapReader::FromBytes(std::move(file), 4, "fuzz");
  if (!reader.ok()) return 0;
  const PriorMapHeader& header = reader->header();
  const std::size_t expected = static_cast<std::size_t>(header.tile_cells()) * header.tile_cells();
  for (int i = 0; i < header.tiles_size() && i < 64; ++i) {
    auto tile = reader->Tile(header.tiles(i).col(), header.tiles(i).row());
    if (tile.ok() && tile->size() != expected) __builtin_trap();
    if (tile.ok()) {
      for (const std::uint8_t cell : *tile) {
        if (cell > 3) __builtin_trap();  // the reader promises classes only
      }
    }
  }
  const GridGeometry g = reader->geometry();
  for (int k = 0; k < 16; ++k) {
    const Eigen::Vector2d p = g.origin + g.resolution_m * Eigen::Vector2d(k * 37 % (g.width + 1), k * 53 % (g.height + 1));
    (void)reader->ClassAt(p);
  }
  for (int i = 0; i < reader->viewpoint_count() && i < 16; ++i) {
    auto cells = reader->ViewpointCells(i);
    if (!cells.ok()) continue;
    const Viewpoint& v = header.viewpoints(i);
    if (cells->size() != static_cast<std::size_t>(v.width()) * static_cast<std::size_t>(v.height())) __builtin_trap();
    for (const std::uint8_t cell : *cells) {
      if (cell > 3) __builtin_trap();
    }
  }
  return 0;
}
