#include "maps/grid/slope_fan_marker.hpp"

#include <cmath>
#include <span>

#include "hal/common/angles.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::maps {

SlopeFanMarker::SlopeFanMarker(const hal::velodyne::LaserTable& table, const StructureGridOptions& options)
    : order_(BottomUpOrder(table)),
      vehicle_T_sensor_(VehicleFromSensor(options.mounting()).cast<float>()),
      thresholds_{.hazard_slope_rad = options.slope().hazard_slope_deg() * kDegToRad,
                  .slammable_slope_rad = options.slope().slammable_slope_deg() * kDegToRad,
                  .fit_points = options.slope().fit_points(),
                  .see_through_max_height_m = options.slope().see_through_max_height_m()},
      fill_in_max_gap_m_(options.fill_in().max_gap_m()),
      fill_in_enabled_(options.fill_in().enabled()),
      free_space_range_m_(options.free_space_range_m()),
      min_range_m_(options.min_range_m()) {}

void SlopeFanMarker::Reset() {
  for (FanMarks& marks : previous_) marks.valid = false;
}

int SlopeFanMarker::CollectBottomUp(const hal::velodyne::Fan& fan) {
  int count = 0;
  for (int i = 0; i < order_.count; ++i) {
    const std::uint8_t laser = order_.bottom_up[static_cast<std::size_t>(i)];
    const hal::velodyne::LaserReturn& r = fan.returns[laser];
    if (!(static_cast<double>(r.range_m) > min_range_m_) || !r.xyz.allFinite()) continue;
    returns_[static_cast<std::size_t>(count)] = vehicle_T_sensor_ * r.xyz;
    laser_of_return_[static_cast<std::size_t>(count)] = laser;
    ++count;
  }
  return count;
}

void SlopeFanMarker::MarkFreeSpace(int count, const Eigen::Isometry2d& grid_T_vehicle, ClassGrid& grid) const {
  // The ground seen along the fan: up to the last free return before the first obstacle.
  double free_range = 0.0;
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
    if (classes_[i] == CellClass::kHazard || classes_[i] == CellClass::kSlammable) break;
    if (classes_[i] != CellClass::kFree) continue;
    const Eigen::Vector2d xy = returns_[i].head<2>().cast<double>();
    if (xy.norm() > free_range) free_range = xy.norm(), direction = xy.normalized();
  }
  if (free_range <= 0.0) return;
  free_range = std::min(free_range, free_space_range_m_);
  grid.MarkLine(grid_T_vehicle.translation(), grid_T_vehicle * (free_range * direction), CellClass::kFree);
}

void SlopeFanMarker::Mark(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle, ClassGrid& grid) {
  const int count = CollectBottomUp(fan);
  const auto n = static_cast<std::size_t>(count);
  ClassifyFan(std::span(returns_).first(n), thresholds_, std::span(classes_).first(n));

  current_.valid = true;
  current_.classes.fill(CellClass::kUnknown);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t laser = laser_of_return_[i];
    current_.positions[laser] = grid_T_vehicle * returns_[i].head<2>().cast<double>();
    current_.classes[laser] = classes_[i];
    if (classes_[i] == CellClass::kHazard || classes_[i] == CellClass::kSlammable) {
      grid.Mark(current_.positions[laser], classes_[i]);
    }
  }
  MarkFreeSpace(count, grid_T_vehicle, grid);

  FanMarks& previous = previous_[static_cast<std::size_t>(fan.kind)];
  if (fill_in_enabled_ && previous.valid) {
    const auto lasers = static_cast<std::size_t>(order_.count);
    FillIn({std::span(previous.positions).first(lasers), std::span(previous.classes).first(lasers)},
           {std::span(current_.positions).first(lasers), std::span(current_.classes).first(lasers)}, fill_in_max_gap_m_,
           grid);
  }
  previous = current_;
}

}  // namespace flat2d::maps
