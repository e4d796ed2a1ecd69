// Clouds of depth images: pi^-1 (Eq. 3.11) of every pixel with a depth, in pixel order,
// and the index image that says which pixel each point came from.
//
// The image's own layout is the index image of 5.1.2 (no re-projection, no depth-buffer
// losses), so statistics and correspondences of a depth frame cost one pass.
#pragma once

#include "hal/cloud/point_cloud.hpp"
#include "maps/range3d/index_image.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

// Points of `depth` (pixels with depth in (0, max_depth_m]) into cloud.points (resized,
// statistics reset) and their pixels into `image`.
void CloudFromDepth(const hal::cloud::DepthImage& depth, const RangeProjection& projection, float max_depth_m,
                    SurfelCloud& cloud, IndexImage& image);

}  // namespace flat2d::maps::range3d
