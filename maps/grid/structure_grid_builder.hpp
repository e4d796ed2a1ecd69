// One revolution's structure grid (thesis 7.1), by the method the options choose: slope
// classes with fill-in and free space (slope_fan_marker.hpp), or the compact voxel popcount,
// Cartesian or polar (voxel_popcount_grid.hpp, polar_voxel_grid.hpp).
//
// The grid is square, size_m on a side, centred on the revolution's reference vehicle pose
// (its frame is the "grid frame"); the caller passes, per fan, the vehicle pose at that fan's
// time in the grid frame (odometry: motion compensation). Begin clears, AddFan works per
// fan as packets arrive, Finish turns popcount columns into classes and returns the grid.
// Every buffer is sized in Create; Begin, AddFan and Finish allocate nothing.
#pragma once

#include <memory>
#include <optional>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/velodyne/fan.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/polar_voxel_grid.hpp"
#include "maps/grid/slope_fan_marker.hpp"
#include "maps/grid/structure_grid_options.pb.h"
#include "maps/grid/voxel_popcount_grid.hpp"

namespace flat2d::maps {

class StructureGridBuilder {
 public:
  // Fails when the options do not validate (structure_grid_config.hpp).
  static Result<StructureGridBuilder> Create(const hal::velodyne::LaserTable& table,
                                             const StructureGridOptions& options);

  void Begin();
  void AddFan(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle);
  const ClassGrid& Finish();

  const ClassGrid& grid() const { return grid_; }
  const StructureGridOptions& options() const { return options_; }

 private:
  StructureGridBuilder(const hal::velodyne::LaserTable& table, const StructureGridOptions& options);
  void AddToPopcount(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle);
  void MarkFreeUpTo(const Eigen::Vector2d& nearest, const Eigen::Isometry2d& grid_T_vehicle);
  CellClass ClassOfColumn(const VoxelColumn& column) const;
  void ClassifyCartesianColumns();
  void ClassifyPolarColumns();

  StructureGridOptions options_;
  Eigen::Isometry3f vehicle_T_sensor_;
  ClassGrid grid_;
  SlopeFanMarker slope_;
  std::optional<VoxelPopcountGrid> cartesian_;  // METHOD_CARTESIAN_POPCOUNT only
  std::optional<PolarVoxelGrid> polar_;         // METHOD_POLAR_POPCOUNT only
  std::uint64_t band_mask_ = 0;
};

// The square grid geometry of the options, centred on the grid frame's origin.
GridGeometry StructureGridGeometry(const StructureGridOptions& options);

}  // namespace flat2d::maps
