// Surface statistics of an unorganized cloud (thesis 5.1.1 without a range image): the
// points within R of each point found with a KD-tree instead of an integral image, then
// the same normal, curvature and information as the organized case (AssignSurface).
//
// For scans with no image model (a triangulation scanner's grid, merged models) and for
// the KD-tree mode of NICP. O(n log n + n k) for k neighbours within R.
#pragma once

#include <Eigen/Core>

#include "maps/range3d/surface_statistics.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

// Fills cloud's normals, curvature and information from cloud.points; normals are
// turned towards `viewpoint` (the scanner's position in the cloud's frame).
void ComputeNeighbourStatistics(const SurfaceStatisticsOptions& options, const Eigen::Vector3f& viewpoint,
                                SurfelCloud& cloud);

}  // namespace flat2d::maps::range3d
