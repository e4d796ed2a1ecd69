// Class grids as map_server files (hal/mapfile/map_server.hpp), with one gray value per class
// so that map_server, RViz and our own tools read them alike:
//   slammable 0 (occupied to map_server), hazard 128 (unknown to map_server, between its
//   thresholds), free 254, unknown 205 (map_server's own unknown value).
// The simulator's truth_map.pgm uses the same values, so it reads back as a ClassGrid.
// Reading maps every other gray value by map_server's trinary thresholds (occupied >= 0.65,
// free <= 0.196 of darkness), so third-party maps read sensibly too.
#pragma once

#include <cstdint>
#include <filesystem>

#include "hal/common/error.hpp"
#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

inline constexpr std::uint8_t kSlammableGray = 0;
inline constexpr std::uint8_t kHazardGray = 128;
inline constexpr std::uint8_t kFreeGray = 254;
inline constexpr std::uint8_t kUnknownGray = 205;

std::uint8_t GrayOf(CellClass cell_class);
CellClass ClassOfGray(std::uint8_t gray);

// Writes <stem>.pgm and <stem>.yaml.
Status WriteClassGrid(const ClassGrid& grid, const std::filesystem::path& stem);
Result<ClassGrid> ReadClassGrid(const std::filesystem::path& yaml_path);

}  // namespace flat2d::maps
