// A recorded drive (Velodyne capture + candump log + DBC) through the map builder
// (localization/mapping/map_builder.hpp): `flat2d-map build --pcap`.
//
// Two passes over the capture. (1) Every complete revolution is gridded with the
// dead-reckoned CAN poses (grid_run.hpp), and its slammable cells, in the vehicle frame,
// are offered to the builder with the revolution's odometry pose; the builder keeps
// keyframes, matches and closes loops. (2) The odometry poses are corrected by the
// optimized keyframes (MapBuilder::CorrectedPose) and the capture is gridded again with
// them, every revolution voting into the mosaic, so the map holds all revolutions, not only
// the keyframes, without keeping any grid in memory between the passes.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/mapping/map_builder.hpp"
#include "localization/tools/grid_run.hpp"
#include "maps/grid/class_grid.hpp"

namespace flat2d::localization {

struct DriveBuildOptions {
  std::filesystem::path capture;
  std::filesystem::path can_log;
  std::filesystem::path dbc;
  std::filesystem::path odometry_config;
  maps::StructureGridOptions grid;
  hal::velodyne::VelodyneStreamOptions stream;
  mapping::MapBuilderOptions builder;
  maps::AccumulationOptions accumulation;
  // A track in the map frame (e.g. GNSS fixes, or the simulator's truth): the first
  // keyframe starts at its pose, and the optimized map is moved by the rigid motion that
  // best fits the keyframes to it. Empty: the odometry frame is the map frame.
  std::vector<evaluation::TimedPose> anchor;
  // A track of positions (GNSS fixes) whose scale the optimized map takes: the least-squares
  // similarity of the keyframes onto it, its scale applied about the keyframes' centroid,
  // before the anchor's rigid fit. Empty: the builder's own scale (odometry and matches).
  std::vector<evaluation::TimedPose> scale_track;
};

struct DriveBuildResult {
  std::vector<evaluation::TimedPose> odometry;  // dead-reckoned, every CAN sample
  std::vector<evaluation::TimedPose> estimate;  // ... corrected
  std::vector<mapping::Keyframe> keyframes;
  mapping::MapBuilderStats stats;
  std::optional<maps::ClassGrid> mosaic;  // none when no revolution fell within the CAN log
  std::uint64_t revolutions = 0;
  // The scale applied from scale_track (1 without one), and the fixes it was fitted on.
  double track_scale = 1.0;
  int track_scale_fixes = 0;
};

// An error when a file cannot be read or is invalid; no keyframes and no mosaic when no
// complete revolution has odometry.
Result<DriveBuildResult> BuildFromDrive(const DriveBuildOptions& options);

}  // namespace flat2d::localization
