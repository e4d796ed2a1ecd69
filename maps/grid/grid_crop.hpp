// Cropping a class grid to the region it observed (issue 6 item 4): the smallest grid of
// whole cells holding every cell that is not unknown, plus a margin, with the origin moved
// so each kept cell stays where it was in the world. A grid that observed nothing crops to
// nothing (nullopt). Files and pictures of a revolution or a drive then hold what was seen,
// not the preallocated square around it.
#pragma once

#include <optional>

#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

std::optional<ClassGrid> CropToObserved(const ClassGrid& grid, int margin_cells = 0);

}  // namespace flat2d::maps
