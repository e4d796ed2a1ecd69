// Viewpoint sub-maps (thesis 7.3.2, Fig. 7.4): what of a map a vehicle at a historic pose of
// the mapping drive could see. The localizer can match a revolution against the viewpoint
// nearest its pose instead of the mosaic, so structure hidden from that pose (the back of a
// wall, a parallel street) cannot attract the match.
//
// VisibleFrom casts rays from the pose over the mosaic, one per `angular_step_rad`, each up
// to range_m or to and including the first slammable cell; every cell a ray crosses keeps its
// class, all others are unknown. The result is the block of the mosaic's cells around the
// pose, aligned with them (as the map file stores it).
#pragma once

#include <Eigen/Core>

#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

ClassGrid VisibleFrom(const ClassGrid& mosaic, const Eigen::Vector2d& position, double range_m,
                      double angular_step_rad = 0.002);

}  // namespace flat2d::maps
