// Marks the fans of a revolution into a class grid with the slope method (thesis 7.1.3),
// hole fill-in between consecutive fans (7.1.4) and free space along each fan.
//
// Steps per fan: (1) take its valid returns bottom-up (laser_order.hpp), dropping those
// nearer than min_range (the vehicle itself), into the ground-level vehicle frame through
// vehicle_T_sensor; (2) classify them (slope_classifier.hpp); (3) place them in the grid with
// the vehicle pose at the fan's own time, grid_T_vehicle, which is the motion compensation;
// (4) mark obstacles, fill in towards the previous fan of the same return kind, and mark
// free the cells from the vehicle to the last free return before the first obstacle (the
// ground the sensor saw), at most free_space_range away. Fixed-size scratch; allocates nothing.
#pragma once

#include <array>

#include <Eigen/Geometry>

#include "hal/velodyne/fan.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/hole_fill_in.hpp"
#include "maps/grid/laser_order.hpp"
#include "maps/grid/slope_classifier.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::maps {

class SlopeFanMarker {
 public:
  // options must have passed ValidateStructureGridOptions.
  SlopeFanMarker(const hal::velodyne::LaserTable& table, const StructureGridOptions& options);

  void Mark(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle, ClassGrid& grid);
  // Forgets the previous fans, so a new revolution does not fill in towards the old one.
  void Reset();

 private:
  struct FanMarks {
    bool valid = false;
    std::array<Eigen::Vector2d, hal::velodyne::kMaxLasers> positions{};  // grid frame, by laser id
    std::array<CellClass, hal::velodyne::kMaxLasers> classes{};          // kUnknown: no return
  };

  int CollectBottomUp(const hal::velodyne::Fan& fan);
  void MarkFreeSpace(int count, const Eigen::Isometry2d& grid_T_vehicle, ClassGrid& grid) const;

  LaserOrder order_;
  Eigen::Isometry3f vehicle_T_sensor_;
  SlopeThresholds thresholds_;
  double fill_in_max_gap_m_;
  bool fill_in_enabled_;
  double free_space_range_m_;
  double min_range_m_;
  // Scratch for one fan, bottom-up (bounded by kMaxLasers).
  std::array<Eigen::Vector3f, hal::velodyne::kMaxLasers> returns_{};
  std::array<std::uint8_t, hal::velodyne::kMaxLasers> laser_of_return_{};
  std::array<CellClass, hal::velodyne::kMaxLasers> classes_{};
  std::array<FanMarks, 2> previous_;  // by ReturnKind: dual-return fans alternate kinds
  FanMarks current_;
};

}  // namespace flat2d::maps
