// A 2D laser log (CARMEN, hal/carmen) through the map builder (map_builder.hpp): issue 8's
// protocol for the public benchmarks. The log's poses are the reference (GMapping-corrected,
// PROVENANCE.md); the odometry the builder sees is that reference corrupted by a seeded
// noise model (odometry_noise.hpp), so the builder's error against the reference is the
// error it adds back. Then every scan is drawn into the mosaic at its corrected pose: free
// cells along each beam, slammable at its end, voted over the scans (GridAccumulator).
#pragma once

#include <cstdint>
#include <vector>

#include "hal/carmen/carmen_log.hpp"
#include "hal/common/error.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/mapping/map_builder.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/grid_accumulator.hpp"

namespace flat2d::localization::mapping {

// The builder settings for 2D laser logs. Their scans are sparse in time (a metre and more
// apart) and a 180-degree scan sees a wall from one side only, so the machinery a
// Velodyne drive needs does them harm: intel's relations error goes from 0.027 m with these
// to 0.12 m with the drive settings (docs/benchmarks.md). Local maps of the last 10
// keyframes, every return counts (no votes: there is no traffic), no refinement sweeps and
// no scale estimate (the noise model's scale error is what the loop closures remove), and
// looser match floors (2 cm, 0.3 deg).
MapBuilderOptions LaserLogBuilderOptions();

struct CarmenBuildOptions {
  MapBuilderOptions builder = LaserLogBuilderOptions();
  OdometryNoiseModel noise;        // corrupts the reference into the builder's odometry
  double min_range_m = 0.05;
  double max_range_m = 40.0;       // longer ranges (a SICK's 81.9 m) are no return
  double mosaic_resolution_m = 0.05;
  maps::AccumulationOptions accumulation;
};

struct CarmenBuildResult {
  // Times are the log's, made strictly increasing: a scan whose time repeats or steps back
  // is put 1 ms after the previous one (counted here).
  std::uint64_t times_adjusted = 0;
  std::vector<evaluation::TimedPose> reference;  // the log's (laser) poses
  std::vector<evaluation::TimedPose> odometry;   // ... corrupted
  std::vector<evaluation::TimedPose> estimate;   // the builder's, every scan
  MapBuilderStats stats;
  std::vector<Keyframe> keyframes;
  maps::ClassGrid mosaic{maps::GridGeometry{}};
};

Result<CarmenBuildResult> BuildFromCarmen(const std::vector<hal::carmen::LaserScan>& scans,
                                          const CarmenBuildOptions& options);

// The points of one scan in the laser frame: finite ranges in [min_range_m, max_range_m].
std::vector<Eigen::Vector2d> ScanPointsOf(const hal::carmen::LaserScan& scan, double min_range_m, double max_range_m);

}  // namespace flat2d::localization::mapping
