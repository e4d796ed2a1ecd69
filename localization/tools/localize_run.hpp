// The work behind `flat2d-localize`: a recorded drive (Velodyne capture + candump log +
// DBC) replayed through the daemon's localization pipeline (localization_pipeline.hpp).
//
// The two files are merged by timestamp, as the daemon receives them live: every CAN frame
// and datagram goes to the pipeline in time order, as fast as possible or at the recorded
// rate. After each new odometry sample the global pose at its time is recorded (poses at
// odometry rate, from the latest L2G: what a client of the daemon would have been told then),
// and each revolution's report is kept for the state timeline and the CPU figures.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/localizer/localizer.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::localization {

struct InitialPoseOptions {
  // The pose, or the track to read it from at the first odometry sample's time (GNSS, or the
  // simulator's truth).
  std::optional<Se2> pose;
  std::vector<evaluation::TimedPose> track;
  // Added to it (x, y in the map frame, heading): a deliberately wrong start.
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double sigma_m = 0.2;
  double sigma_rad = 0.02;
};

// The initial pose at `time_s` (the first odometry sample's, or the first revolution's), with
// the offset added; an error naming `what` when the track does not cover that time.
Result<Se2> InitialPoseAt(const InitialPoseOptions& initial, double time_s, const std::string& what);

struct LocalizeRunOptions {
  std::filesystem::path capture;
  std::filesystem::path can_log;
  std::filesystem::path dbc;
  std::filesystem::path odometry_config;
  std::filesystem::path map;
  maps::StructureGridOptions grid;
  hal::velodyne::VelodyneStreamOptions stream;
  LocalizerOptions localizer;
  InitialPoseOptions initial;
  bool realtime = false;  // pace the inputs at their recorded rate
};

struct RevolutionRecord {
  double time_s = 0.0;  // the grid's first fan
  RevolutionReport report;
};

struct LocalizeRunResult {
  std::vector<evaluation::TimedPose> estimate;  // global, at odometry rate, once there is a fix
  // Dead reckoning alone from the same initial pose (open loop), in the map frame.
  std::vector<evaluation::TimedPose> odometry;
  std::vector<RevolutionRecord> revolutions;
  LocalizerStats stats;
  double first_fix_s = 0.0;  // when the initial pose took effect (first grid)
};

// An error when a file cannot be read or is invalid, or no initial pose is given or found.
Result<LocalizeRunResult> RunLocalization(const LocalizeRunOptions& options);

}  // namespace flat2d::localization
