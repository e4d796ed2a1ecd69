#include "maps/prior_map/prior_map_region.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace flat2d::maps {

std::optional<MapRegion> StoredExtent(const PriorMapReader& reader) {
  const PriorMapHeader& h = reader.header();
  if (h.tiles_size() == 0) return std::nullopt;
  int col0 = h.width_tiles(), row0 = h.height_tiles(), col1 = -1, row1 = -1;
  for (const TileEntry& tile : h.tiles()) {
    col0 = std::min(col0, tile.col());
    row0 = std::min(row0, tile.row());
    col1 = std::max(col1, tile.col());
    row1 = std::max(row1, tile.row());
  }
  const double side = h.resolution_m() * h.tile_cells();
  const Eigen::Vector2d origin(h.origin_x_m(), h.origin_y_m());
  return MapRegion{origin + side * Eigen::Vector2d(col0, row0), origin + side * Eigen::Vector2d(col1 + 1, row1 + 1)};
}

Result<ClassGrid> ReadRegion(PriorMapReader& reader, const MapRegion& region, std::size_t max_cells) {
  const GridGeometry map = reader.geometry();
  const double r = map.resolution_m;
  auto col_of = [&](double x) { return std::clamp(std::floor((x - map.origin.x()) / r), 0.0, double(map.width)); };
  auto row_of = [&](double y) { return std::clamp(std::floor((y - map.origin.y()) / r), 0.0, double(map.height)); };
  const auto col0 = static_cast<int>(col_of(region.low.x())), col1 = static_cast<int>(std::ceil(col_of(region.high.x())));
  const auto row0 = static_cast<int>(row_of(region.low.y())), row1 = static_cast<int>(std::ceil(row_of(region.high.y())));
  if (!(region.low.array() < region.high.array()).all() || col1 <= col0 || row1 <= row0) {
    return MakeError("region does not overlap the map");
  }
  GridGeometry g;
  g.resolution_m = r;
  g.width = col1 - col0;
  g.height = row1 - row0;
  g.origin = map.origin + r * Eigen::Vector2d(col0, row0);
  if (g.cell_count() > max_cells) {
    return MakeError("region of " + std::to_string(g.width) + " x " + std::to_string(g.height) +
                     " cells is larger than " + std::to_string(max_cells) + ": choose a smaller --region");
  }
  ClassGrid grid(g);
  const int n = reader.header().tile_cells();
  for (int tile_row = row0 / n; tile_row <= (row1 - 1) / n; ++tile_row) {
    for (int tile_col = col0 / n; tile_col <= (col1 - 1) / n; ++tile_col) {
      auto tile = reader.Tile(tile_col, tile_row);
      if (!tile.ok()) return tile.error();
      for (int r_in = 0; r_in < n; ++r_in) {
        const int row = tile_row * n + r_in;
        if (row < row0 || row >= row1) continue;
        for (int c_in = 0; c_in < n; ++c_in) {
          const int col = tile_col * n + c_in;
          if (col < col0 || col >= col1) continue;
          const auto value = static_cast<CellClass>((*tile)[static_cast<std::size_t>(r_in * n + c_in)]);
          if (value != CellClass::kUnknown) grid.Mark(CellIndex{col - col0, row - row0}, value);
        }
      }
    }
  }
  return grid;
}

}  // namespace flat2d::maps
