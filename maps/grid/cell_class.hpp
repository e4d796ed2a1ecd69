// The classes of a structure grid cell (thesis 7.1.3): what navigation and scan matching
// each need from one map. Ordered by precedence: when two observations mark one cell, the
// higher class wins (a wall seen once is a wall, even where the floor was seen free).
#pragma once

#include <algorithm>
#include <cstdint>

namespace flat2d::maps {

enum class CellClass : std::uint8_t {
  kUnknown = 0,    // never observed
  kFree = 1,       // observed traversable ground
  kHazard = 2,     // an obstacle to navigation (slope above the hazard threshold)
  kSlammable = 3,  // vertical structure, reliable for scan matching
};

inline CellClass Strongest(CellClass a, CellClass b) { return std::max(a, b); }

}  // namespace flat2d::maps
