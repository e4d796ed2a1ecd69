#include "maps/render/class_grid_image.hpp"

namespace flat2d::maps {

Rgb ColourOf(CellClass cell_class) {
  switch (cell_class) {
    case CellClass::kSlammable: return kSlammableColour;
    case CellClass::kHazard: return kHazardColour;
    case CellClass::kFree: return kFreeColour;
    case CellClass::kUnknown: break;
  }
  return kUnknownColour;
}

RgbImage RenderClassGrid(const ClassGrid& grid) {
  const GridGeometry& geometry = grid.geometry();
  RgbImage image(geometry.width, geometry.height, kUnknownColour);
  for (int row = 0; row < geometry.height; ++row) {
    for (int col = 0; col < geometry.width; ++col) {
      image.Set(col, geometry.height - 1 - row, ColourOf(grid.at({col, row})));
    }
  }
  return image;
}

}  // namespace flat2d::maps
