// Hole fill-in between consecutive vertical fans (thesis 7.1.4): a 16- or 32-laser sensor
// samples much more densely in azimuth than in elevation, yet at 15 m consecutive fans' returns
// are already 10 cm apart, leaving holes a scan matcher cannot match across.
//
// For each laser, when its returns in two consecutive fans have the same obstacle class and
// lie less than max_gap_m apart (25 cm by default), the cells on the segment between them get
// that class. The distance bound keeps fill-in from bridging real gaps (doorways, a fence's
// pickets). Free returns are not joined: free space comes from ray casting.
#pragma once

#include <span>

#include <Eigen/Core>

#include "maps/grid/cell_class.hpp"
#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

// One fan's classified returns, indexed by laser id; an unclassified (missing) return is
// kUnknown.
struct ClassifiedFan {
  std::span<const Eigen::Vector2d> positions;  // grid frame
  std::span<const CellClass> classes;
};

// Draws the fill-in segments, shorter than max_gap_m, between `previous` and `current` (same
// laser count) into grid; returns how many segments it drew.
int FillIn(const ClassifiedFan& previous, const ClassifiedFan& current, double max_gap_m, ClassGrid& grid);

}  // namespace flat2d::maps
