#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

class ClassGridTiles final : public TileSource {
 public:
  explicit ClassGridTiles(const ClassGrid& grid) : grid_(grid) {}
  const GridGeometry& geometry() const override { return grid_.geometry(); }
  bool FillTile(int tile_cells, int tile_col, int tile_row, std::span<std::uint8_t> cells) override {
    bool any = false;
    for (int r = 0; r < tile_cells; ++r) {
      for (int c = 0; c < tile_cells; ++c) {
        const CellIndex cell{tile_col * tile_cells + c, tile_row * tile_cells + r};
        const CellClass value = grid_.geometry().Contains(cell) ? grid_.at(cell) : CellClass::kUnknown;
        cells[static_cast<std::size_t>(r * tile_cells + c)] = static_cast<std::uint8_t>(value);
        any = any || value != CellClass::kUnknown;
      }
    }
    return any;
  }

 private:
  const ClassGrid& grid_;
};

std::uint32_t Crc32(const char* bytes, std::size_t size) {
  return static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(bytes), static_cast<uInt>(size)));
}

// Appends the zstd frame of `cells` to `section`; its size, or an error.
Result<std::size_t> AppendCompressed(std::span<const std::uint8_t> cells, int level, std::vector<char>& scratch,
                                     std::string& section) {
  scratch.resize(ZSTD_compressBound(cells.size()));
  const std::size_t size = ZSTD_compress(scratch.data(), scratch.size(), cells.data(), cells.size(), level);
  if (ZSTD_isError(size)) return MakeError(std::string("prior map: zstd: ") + ZSTD_getErrorName(size));
  section.append(scratch.data(), size);
  return size;
}

Status AddViewpoints(std::span<const ViewpointGrid> viewpoints, const GridGeometry& map, int level,
                     PriorMapHeader& header, std::string& section) {
  std::vector<char> scratch;
  std::vector<std::uint8_t> cells;
  for (const ViewpointGrid& viewpoint : viewpoints) {
    const GridGeometry& g = viewpoint.cells.geometry();
    const Eigen::Vector2d offset = (g.origin - map.origin) / map.resolution_m;
    const Eigen::Vector2d rounded = offset.array().round();
    if (std::abs(g.resolution_m - map.resolution_m) > 1e-9 || (offset - rounded).cwiseAbs().maxCoeff() > 1e-3 ||
        g.width > kMaxViewpointSideCells || g.height > kMaxViewpointSideCells) {
      return MakeError("prior map: a viewpoint's cells must line up with the map's and be at most " +
                       std::to_string(kMaxViewpointSideCells) + " cells a side");
    }
    cells.resize(g.cell_count());
    std::transform(viewpoint.cells.cells().begin(), viewpoint.cells.cells().end(), cells.begin(),
                   [](CellClass c) { return static_cast<std::uint8_t>(c); });
    Viewpoint* entry = header.add_viewpoints();
    entry->set_x_m(viewpoint.x_m);
    entry->set_y_m(viewpoint.y_m);
    entry->set_yaw_rad(viewpoint.yaw_rad);
    entry->set_time_s(viewpoint.time_s);
    entry->set_col(static_cast<int>(rounded.x()));
    entry->set_row(static_cast<int>(rounded.y()));
    entry->set_width(g.width);
    entry->set_height(g.height);
    entry->set_offset(section.size());
    auto size = AppendCompressed(cells, level, scratch, section);
    if (!size.ok()) return size.error();
    entry->set_compressed_bytes(static_cast<std::uint32_t>(*size));
    entry->set_crc32(Crc32(section.data() + entry->offset(), *size));
  }
  return Status::Ok();
}

}  // namespace

Status WritePriorMap(const ClassGrid& grid, const std::filesystem::path& path, const PriorMapWriteOptions& options,
                     std::span<const ViewpointGrid> viewpoints) {
  ClassGridTiles tiles(grid);
  return WritePriorMap(tiles, path, options, viewpoints);
}

Status WritePriorMap(TileSource& source, const std::filesystem::path& path, const PriorMapWriteOptions& options,
                     std::span<const ViewpointGrid> viewpoints) {
  const GridGeometry& g = source.geometry();
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

  const auto tile_bytes = static_cast<std::size_t>(options.tile_cells) * static_cast<std::size_t>(options.tile_cells);
  std::vector<std::uint8_t> cells(tile_bytes);
  std::vector<char> scratch;
  std::string section;
  std::uint64_t mapped = 0, slammable = 0;
  for (int row = 0; row < header.height_tiles(); ++row) {
    for (int col = 0; col < header.width_tiles(); ++col) {
      if (!source.FillTile(options.tile_cells, col, row, cells)) continue;
      mapped += static_cast<std::uint64_t>(
          std::count_if(cells.begin(), cells.end(), [](std::uint8_t c) { return c != 0; }));
      slammable += static_cast<std::uint64_t>(std::count(cells.begin(), cells.end(),
                                                         static_cast<std::uint8_t>(CellClass::kSlammable)));
      TileEntry* entry = header.add_tiles();
      entry->set_col(col);
      entry->set_row(row);
      entry->set_offset(section.size());
      auto size = AppendCompressed(cells, options.zstd_level, scratch, section);
      if (!size.ok()) return size.error();
      entry->set_compressed_bytes(static_cast<std::uint32_t>(*size));
      entry->set_crc32(Crc32(section.data() + entry->offset(), *size));
    }
  }
  header.set_mapped_cells(mapped);
  header.set_slammable_cells(slammable);
  if (Status added = AddViewpoints(viewpoints, g, options.zstd_level, header, section); !added.ok()) return added;

  const std::string header_bytes = header.SerializeAsString();
  std::string preamble(kPriorMapMagic, sizeof(kPriorMapMagic));
  AppendLittleEndian(preamble, kPriorMapFormatVersion);
  AppendLittleEndian(preamble, static_cast<std::uint32_t>(header_bytes.size()));
  AppendLittleEndian(preamble, Crc32(header_bytes.data(), header_bytes.size()));
  // Written beside the target and renamed over it, so a reader never sees half a map.
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) return MakeError(partial.string() + ": cannot write");
    out << preamble << header_bytes << section;
    out.close();
    if (!out) return MakeError(partial.string() + ": write failed");
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) return MakeError(path.string() + ": " + error.message());
  return Status::Ok();
}

}  // namespace flat2d::maps
