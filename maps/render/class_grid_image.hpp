// A class grid as a picture in the thesis' colours (Figs. 7.2, 7.6): black slammable
// structure, red hazard, white observed free space, light grey unknown. One pixel per cell,
// north up: the grid's top row (highest y) is the image's first row.
#pragma once

#include "maps/grid/class_grid.hpp"
#include "maps/render/image.hpp"

namespace flat2d::maps {

inline constexpr Rgb kSlammableColour{0, 0, 0};
inline constexpr Rgb kHazardColour{220, 30, 30};
inline constexpr Rgb kFreeColour{255, 255, 255};
inline constexpr Rgb kUnknownColour{200, 200, 200};

Rgb ColourOf(CellClass cell_class);

RgbImage RenderClassGrid(const ClassGrid& grid);

}  // namespace flat2d::maps
