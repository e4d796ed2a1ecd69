#include "maps/grid/class_grid_file.hpp"

#include <string>
#include <vector>

#include "hal/mapfile/map_server.hpp"

namespace flat2d::maps {

std::uint8_t GrayOf(CellClass cell_class) {
  switch (cell_class) {
    case CellClass::kSlammable: return kSlammableGray;
    case CellClass::kHazard: return kHazardGray;
    case CellClass::kFree: return kFreeGray;
    case CellClass::kUnknown: break;
  }
  return kUnknownGray;
}

CellClass ClassOfGray(std::uint8_t gray) {
  switch (gray) {
    case kSlammableGray: return CellClass::kSlammable;
    case kHazardGray: return CellClass::kHazard;
    case kFreeGray: return CellClass::kFree;
    case kUnknownGray: return CellClass::kUnknown;
    default: break;
  }
  const double darkness = (255.0 - gray) / 255.0;  // map_server, negate 0
  if (darkness >= 0.65) return CellClass::kSlammable;
  if (darkness <= 0.196) return CellClass::kFree;
  return CellClass::kUnknown;
}

Status WriteClassGrid(const ClassGrid& grid, const std::filesystem::path& stem) {
  const GridGeometry& g = grid.geometry();
  hal::mapfile::GrayMap map{.width = g.width, .height = g.height, .resolution_m = g.resolution_m,
                            .origin = g.origin, .pixels = {}};
  map.pixels.reserve(g.cell_count());
  for (int row = g.height - 1; row >= 0; --row) {
    for (int col = 0; col < g.width; ++col) map.pixels.push_back(GrayOf(grid.at({col, row})));
  }
  return hal::mapfile::WriteMapServer(
      map, stem,
      {"flat2d structure grid: " + std::to_string(kSlammableGray) + " slammable, " + std::to_string(kHazardGray) +
       " hazard, " + std::to_string(kFreeGray) + " free, " + std::to_string(kUnknownGray) + " unknown"});
}

Result<ClassGrid> ReadClassGrid(const std::filesystem::path& yaml_path) {
  auto map = hal::mapfile::ReadMapServer(yaml_path);
  if (!map.ok()) return map.error();
  ClassGrid grid(GridGeometry{.width = map->width, .height = map->height, .resolution_m = map->resolution_m,
                              .origin = map->origin});
  for (int row = 0; row < map->height; ++row) {
    for (int col = 0; col < map->width; ++col) {
      const std::size_t pixel = static_cast<std::size_t>(map->height - 1 - row) * static_cast<std::size_t>(map->width) +
                                static_cast<std::size_t>(col);
      grid.Mark(CellIndex{col, row}, ClassOfGray(map->pixels[pixel]));
    }
  }
  return grid;
}

}  // namespace flat2d::maps
