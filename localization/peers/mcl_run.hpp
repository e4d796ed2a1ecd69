// The Monte-Carlo localization peer of issue 9: MRPT's CMonteCarloLocalization2D (particle
// filter, likelihood field) on a recorded drive, against an occupancy grid made from the
// same prior map flat2d-localize uses, with the same inputs:
//
//   candump log --CanOdometry--> dead-reckoned poses (local frame)
//   Velodyne capture --RunGrid--> one structure grid per revolution, motion-compensated
//     with those poses; its slammable cells --StructureScan--> a 360-degree range scan
//   per revolution: the odometry since the last revolution (CActionRobotMovement2D,
//     Gaussian motion model) and the scan --particle filter--> the particles' mean pose
//
// The filter starts around a given pose (a track read at the first revolution's time), as
// flat2d-localize does with --initial-from. CPU time is the filter's step per revolution
// (thread CPU time), the figure to put beside flat2d-localize's match + solve.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/peers/occupancy_from_prior_map.hpp"
#include "localization/peers/structure_scan.hpp"
#include "localization/tools/localize_run.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::localization::peers {

struct MclOptions {
  int particles = 1000;
  double occupancy_resolution_m = 0.10;
  // Likelihood field (MRPT's lmLikelihoodField_Thrun).
  float hit_sigma_m = 0.35f;  // MRPT's default; 0.2 lost the campus track more often
  float max_correspondence_m = 0.5f;
  int ray_decimation = 2;
  // Gaussian motion model: position sigma per metre driven, heading sigma per metre and per
  // radian turned, and their floors per step.
  double xy_sigma_per_m = 0.02;
  double heading_sigma_per_m = 0.005;
  double heading_sigma_per_rad = 0.05;
  double min_xy_sigma_m = 0.02;
  double min_heading_sigma_rad = 0.004;
  unsigned seed = 1;
};

struct MclRunOptions {
  std::filesystem::path capture;
  std::filesystem::path can_log;
  std::filesystem::path dbc;
  std::filesystem::path odometry_config;
  std::filesystem::path map;
  maps::StructureGridOptions grid;
  hal::velodyne::VelodyneStreamOptions stream;
  InitialPoseOptions initial;  // read at the first revolution, as flat2d-localize does
  MclOptions mcl;
  StructureScanOptions scan;
};

struct MclRunResult {
  std::vector<evaluation::TimedPose> estimate;  // the particles' mean, map frame, per revolution
  std::vector<double> step_cpu_ms;              // the filter's step per revolution
  std::vector<int> scan_returns;                // rays with a return per revolution
  OccupancyStats occupancy;
  double occupancy_cpu_ms = 0.0;  // making the occupancy grid from the map, once
  std::uint64_t revolutions = 0;  // complete revolutions gridded
};

// An error when a file cannot be read or is invalid, or the track does not cover the first
// revolution.
Result<MclRunResult> RunMcl(const MclRunOptions& options);

}  // namespace flat2d::localization::peers
