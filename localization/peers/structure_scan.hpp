// A revolution's structure grid as a 2D range scan, for the Monte-Carlo localization peer:
// the slammable cells (the points flat2d's own matcher uses) binned by bearing around the
// vehicle, the nearest per bin, as a 360-degree laser would return them. The default bins
// are fine (1/16 degree: a 5 cm cell at 45 m) so that the scan keeps about every cell that is
// not behind a nearer one; at 0.5 degree a campus scan kept 149 of its cells and MRPT lost
// the track (docs/benchmarks.md).
#pragma once

#include <mrpt/obs/CObservation2DRangeScan.h>

#include "maps/grid/class_grid.hpp"

namespace flat2d::localization::peers {

struct StructureScanOptions {
  int rays = 5760;          // over the full turn (1/16 degree)
  float max_range_m = 60.0f;
  float min_range_m = 1.0f;  // the vehicle's own body
};

// Fills `scan` (resized to options.rays) from `grid`, a revolution's grid in the vehicle
// frame at its first fan; returns how many rays have a return.
int StructureScan(const maps::ClassGrid& grid, const StructureScanOptions& options,
                  mrpt::obs::CObservation2DRangeScan& scan);

// The bearing (radians, vehicle frame) of ray `index` of an N-ray full-turn scan, as MRPT
// lays them out: from -pi, counter-clockwise, aperture / (N - 1) apart.
double RayBearing(int index, int rays);

}  // namespace flat2d::localization::peers
