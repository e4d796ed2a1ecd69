#include <zlib.h>
#include <zstd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "maps/prior_map/prior_map_file.hpp"

namespace flat2d::maps {
namespace {

void AppendLittleEndian(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
}

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The cells of tile (col, row), unknown beyond the grid; false when all are unknown.
bool TileCells(const ClassGrid& grid, int tile_cells, int tile_col, int tile_row, std::vector<std::uint8_t>& cells) {
  bool any = false;
  for (int r = 0; r < tile_cells; ++r) {
    for (int c = 0; c < tile_cells; ++c) {
      const CellIndex cell{tile_col * tile_cells + c, tile_row * tile_cells + r};
      const CellClass value = grid.geometry().Contains(cell) ? grid.at(cell) : CellClass::kUnknown;
      cells[static_cast<std::size_t>(r * tile_cells + c)] = static_cast<std::uint8_t>(value);
      any = any || value != CellClass::kUnknown;
    }
  }
  return any;
}

}  // namespace

Status WritePriorMap(const ClassGrid& grid, const std::filesystem::path& path, const PriorMapWriteOptions& options) {
  const GridGeometry& g = grid.geometry();
  if (options.tile_cells < 16 || options.tile_cells > kMaxTileCells) {
    return MakeError("prior map: tile_cells must be in [16, " + std::to_string(kMaxTileCells) + "]");
  }
  if (!(g.resolution_m > 0.0) || g.width <= 0 || g.height <= 0) return MakeError("prior map: empty grid");

  PriorMapHeader header;
  header.set_format_version(kPriorMapFormatVersion);
  header.set_resolution_m(g.resolution_m);
  header.set_tile_cells(options.tile_cells);
  header.set_origin_x_m(g.origin.x());
  header.set_origin_y_m(g.origin.y());
  header.set_width_tiles((g.width + options.tile_cells - 1) / options.tile_cells);
  header.set_height_tiles((g.height + options.tile_cells - 1) / options.tile_cells);
  *header.mutable_georeference() = options.georeference;
  auto& legend = *header.mutable_legend();
  legend[0] = "unknown";
  legend[1] = "free";
  legend[2] = "hazard";
  legend[3] = "slammable";
  header.set_created_by(options.created_by);
  header.set_created_utc(options.created_utc.empty() ? UtcNow() : options.created_utc);
  header.set_source(options.source);
  header.set_mapped_cells(g.cell_count() - grid.Count(CellClass::kUnknown));

  const auto tile_bytes = static_cast<std::size_t>(options.tile_cells) * static_cast<std::size_t>(options.tile_cells);
  std::vector<std::uint8_t> cells(tile_bytes);
  std::string tiles;
  std::vector<char> compressed(ZSTD_compressBound(tile_bytes));
  for (int row = 0; row < header.height_tiles(); ++row) {
    for (int col = 0; col < header.width_tiles(); ++col) {
      if (!TileCells(grid, options.tile_cells, col, row, cells)) continue;
      const std::size_t size =
          ZSTD_compress(compressed.data(), compressed.size(), cells.data(), cells.size(), options.zstd_level);
      if (ZSTD_isError(size)) return MakeError(std::string("prior map: zstd: ") + ZSTD_getErrorName(size));
      TileEntry* entry = header.add_tiles();
      entry->set_col(col);
      entry->set_row(row);
      entry->set_offset(tiles.size());
      entry->set_compressed_bytes(static_cast<std::uint32_t>(size));
      entry->set_crc32(static_cast<std::uint32_t>(
          crc32(0L, reinterpret_cast<const Bytef*>(compressed.data()), static_cast<uInt>(size))));
      tiles.append(compressed.data(), size);
    }
  }

  const std::string header_bytes = header.SerializeAsString();
  std::string preamble(kPriorMapMagic, sizeof(kPriorMapMagic));
  AppendLittleEndian(preamble, kPriorMapFormatVersion);
  AppendLittleEndian(preamble, static_cast<std::uint32_t>(header_bytes.size()));
  AppendLittleEndian(preamble, static_cast<std::uint32_t>(
                                   crc32(0L, reinterpret_cast<const Bytef*>(header_bytes.data()),
                                         static_cast<uInt>(header_bytes.size()))));
  // Written beside the target and renamed over it, so a reader never sees half a map.
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) return MakeError(partial.string() + ": cannot write");
    out << preamble << header_bytes << tiles;
    out.close();
    if (!out) return MakeError(partial.string() + ": write failed");
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) return MakeError(path.string() + ": " + error.message());
  return Status::Ok();
}

}  // namespace flat2d::maps
