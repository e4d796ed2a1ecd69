// The work behind `flat2d-grid`: a Velodyne capture through the structure-grid pipeline
// (thesis 7.1), either one revolution's grid or every revolution accumulated into one grid.
//
// Steps: (1) the capture's datagrams go through VelodyneStream (decoding, time, revolution
// cuts); (2) once the model is known, a RevolutionGridder of that model's laser table builds
// one grid per revolution, each fan placed with the vehicle pose at its own time when poses
// are given (truth, estimate or dead-reckoned CAN: motion compensation); (3) either the
// requested complete revolution is kept, or every complete revolution's grid votes into one
// grid covering the poses (GridAccumulator), in the poses' frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/grid_accumulator.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/revolution_gridder.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::localization {

struct GridRunOptions {
  std::filesystem::path capture;
  maps::StructureGridOptions grid;
  hal::velodyne::VelodyneStreamOptions stream;
  // Vehicle poses over the capture's time (empty: the sensor is taken as standing still).
  std::vector<maps::StampedPose2d> poses;
  bool accumulate = false;  // every complete revolution into one grid (needs poses)
  int revolution = 0;       // otherwise: which complete revolution to keep
  maps::AccumulationOptions accumulation;
  // Called with every complete revolution's grid (the evaluation tools look at each).
  std::function<void(const maps::PublishedGrid&)> on_grid;
};

struct GridRunResult {
  // The kept revolution's grid, in its own frame (the vehicle at its first fan), or the
  // accumulated grid in the poses' frame.
  std::optional<maps::ClassGrid> grid;
  // The kept revolution's reference pose in the poses' frame (identity when accumulating).
  Eigen::Isometry2d frame_T_grid = Eigen::Isometry2d::Identity();
  TimeNs grid_start_ns = 0;
  TimeNs grid_end_ns = 0;
  // False when the capture holds no complete revolution and the kept grid is its first
  // partial one (short captures, FOV-limited sensors).
  bool grid_complete = true;
  // Set when the capture's model cannot be decoded (e.g. VLS-128): no grid.
  std::optional<std::string> unsupported;
  std::uint64_t grids_complete = 0;     // complete revolutions gridded
  std::uint64_t grids_accumulated = 0;  // ... of which had a pose and were accumulated
  // Fans placed at their revolution's reference pose for want of a pose at their time: of
  // the kept revolution, or of every revolution when accumulating.
  std::uint64_t fans_without_pose = 0;
  hal::velodyne::VelodyneStreamStats stream;
  std::optional<hal::velodyne::Identification> identification;
};

Result<GridRunResult> RunGrid(const GridRunOptions& options);

// The capture gridded again at poses found by a 3D build (world_T_vehicle at revolution
// stamps, flattened), every revolution voting into one mosaic: the map of `flat2d-map build
// --mode nicp|landmarks`. Empty when nothing was gridded.
Result<std::optional<maps::ClassGrid>> GridCaptureAtPoses(const std::filesystem::path& capture,
                                                          const maps::StructureGridOptions& grid,
                                                          const hal::velodyne::VelodyneStreamOptions& stream,
                                                          const maps::AccumulationOptions& accumulation,
                                                          const std::vector<hal::trajectory::StampedPose>& trajectory);

// The world grid that covers every pose with `margin_m` to spare, at `resolution_m`.
maps::GridGeometry CoveringGeometry(const std::vector<maps::StampedPose2d>& poses,
                                    double resolution_m, double margin_m);

}  // namespace flat2d::localization
