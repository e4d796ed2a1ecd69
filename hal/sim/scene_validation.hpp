// Checks a SceneDescription before the Scene compiles it (internal to the Scene).
//
// Every number must be finite; sizes positive; polylines need enough points and no
// zero-length segments where a segment becomes a solid; building outlines must be simple
// polygons with non-zero area; ramps need slopes in (0, 45) degrees; reflectivities fit a
// byte; a moving object needs a shape and a path. The first problem found is returned,
// naming the element and field as a path into the description, e.g.
// "boxes[2].height_m: must be positive and finite".
#pragma once

#include "hal/common/error.hpp"
#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim::internal {

Status ValidateScene(const SceneDescription& description);

}  // namespace flat2d::hal::sim::internal
