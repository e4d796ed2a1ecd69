// `flat2d-map build --mode landmarks DRIVE`: a Velodyne drive mapped by 3D line and plane
// landmark SLAM (thesis 8.2) over CAN odometry, and the 2D prior map gridded at the poses it
// found.
//
// Steps: (1) every complete revolution deskewed by the CAN odometry into the sensor frame of
// its first fan (deskewed_drive.hpp, shared with the NARF key-point peer); (2) its lines and planes extracted (thesis 8.1,
// maps/features3d); (3) the features and the odometry pose at the revolution's stamp handed
// to the landmark graph (localization/landmarks/landmark_slam.hpp: odometry factors between
// pose nodes, features associated with the landmarks near their prediction or made new
// landmarks, a robust kernel, Gauss-Newton on the manifolds of App. A), the graph optimized
// as it grows and once more at the end; (4) the capture gridded again at the optimized poses
// into the map's mosaic (grid_run.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/landmarks/landmark_slam.hpp"
#include "maps/features3d/feature_options.pb.h"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/grid_accumulator.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::localization::tools {

struct LandmarkDriveOptions {
  std::filesystem::path capture;
  std::filesystem::path can_log, dbc, odometry_config;  // CAN odometry: required
  maps::StructureGridOptions grid;  // the sensor's mounting and the map's grids
  hal::velodyne::VelodyneStreamOptions stream;
  maps::features3d::FeatureExtractionOptions features;
  landmarks::LandmarkSlamOptions slam;
  // The first revolution's vehicle pose (a truth or GNSS track); empty: the odometry's.
  std::vector<evaluation::TimedPose> anchor;
  int max_revolutions = 0;  // 0: every complete revolution
  bool build_map = true;
  maps::AccumulationOptions accumulation;
};

struct LandmarkDriveResult {
  std::vector<hal::trajectory::StampedPose> trajectory;  // world_T_vehicle per revolution
  std::vector<hal::trajectory::StampedPose> odometry;    // the CAN odometry from the same first pose
  std::vector<landmarks::LandmarkSlam::PlaneLandmark> planes;
  std::vector<landmarks::LandmarkSlam::LineLandmark> lines;
  landmarks::LandmarkSlamStats stats;
  std::string sensor;
  int revolutions = 0;
  int revolutions_without_odometry = 0;  // outside the CAN log's time: skipped
  std::vector<double> features_ms;  // per revolution: deskewed cloud + extraction
  std::vector<double> slam_ms;      // per revolution: the graph's share (optimizations included)
  double finish_ms = 0.0;           // the final optimization
  std::optional<maps::ClassGrid> mosaic;
  double grid_seconds = 0.0;
};

// Errors name the file: the capture, CAN log, DBC or odometry configuration unreadable, an
// unsupported model, no complete revolution.
Result<LandmarkDriveResult> BuildLandmarkDrive(const LandmarkDriveOptions& options);

}  // namespace flat2d::localization::tools
