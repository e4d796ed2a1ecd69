#include "maps/grid/structure_grid_builder.hpp"

#include <algorithm>
#include <cmath>

#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::maps {

GridGeometry StructureGridGeometry(const StructureGridOptions& options) {
  const int cells = static_cast<int>(std::ceil(options.size_m() / options.resolution_m()));
  const double half = 0.5 * cells * options.resolution_m();
  return GridGeometry{.width = cells, .height = cells, .resolution_m = options.resolution_m(),
                      .origin = Eigen::Vector2d(-half, -half)};
}

Result<StructureGridBuilder> StructureGridBuilder::Create(const hal::velodyne::LaserTable& table,
                                                          const StructureGridOptions& options) {
  if (Status valid = ValidateStructureGridOptions(options); !valid.ok()) return valid.error();
  return StructureGridBuilder(table, options);
}

StructureGridBuilder::StructureGridBuilder(const hal::velodyne::LaserTable& table,
                                           const StructureGridOptions& options)
    : options_(options),
      vehicle_T_sensor_(VehicleFromSensor(options.mounting()).cast<float>()),
      grid_(StructureGridGeometry(options)),
      slope_(table, options) {
  const PopcountOptions& popcount = options.popcount();
  const auto band_height = static_cast<float>(popcount.band_height_m());
  band_mask_ = BandMask(static_cast<float>(popcount.band_low_m()), static_cast<float>(popcount.band_high_m()),
                        band_height);
  if (options.method() == StructureGridOptions::METHOD_CARTESIAN_POPCOUNT) {
    cartesian_.emplace(grid_.geometry(), band_height);
  } else if (options.method() == StructureGridOptions::METHOD_POLAR_POPCOUNT) {
    const PolarGridLayout layout{
        .azimuth_bins = popcount.polar_azimuth_bins(),
        .range_bins = static_cast<int>(std::ceil(0.5 * options.size_m() / popcount.polar_range_resolution_m())),
        .range_resolution_m = popcount.polar_range_resolution_m()};
    polar_.emplace(layout, band_height);
  }
}

void StructureGridBuilder::Begin() {
  grid_.Clear();
  slope_.Reset();
  if (cartesian_) cartesian_->Clear();
  if (polar_) polar_->Clear();
}

void StructureGridBuilder::AddFan(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle) {
  if (options_.method() == StructureGridOptions::METHOD_SLOPE) {
    slope_.Mark(fan, grid_T_vehicle, grid_);
  } else {
    AddToPopcount(fan, grid_T_vehicle);
  }
}

void StructureGridBuilder::AddToPopcount(const hal::velodyne::Fan& fan, const Eigen::Isometry2d& grid_T_vehicle) {
  const Eigen::Isometry2f grid_T_vehicle_f = grid_T_vehicle.cast<float>();
  const auto min_range = static_cast<float>(options_.min_range_m());
  Eigen::Vector2f nearest = Eigen::Vector2f::Zero();  // vehicle frame
  for (int laser = 0; laser < fan.num_lasers; ++laser) {
    const hal::velodyne::LaserReturn& r = fan.returns[static_cast<std::size_t>(laser)];
    if (!(r.range_m > min_range) || !r.xyz.allFinite()) continue;
    const Eigen::Vector3f vehicle = vehicle_T_sensor_ * r.xyz;
    if (nearest.isZero() || vehicle.head<2>().squaredNorm() < nearest.squaredNorm()) nearest = vehicle.head<2>();
    const Eigen::Vector2f xy = grid_T_vehicle_f * vehicle.head<2>();
    const Eigen::Vector3f point(xy.x(), xy.y(), vehicle.z());
    if (cartesian_) cartesian_->Add(point);
    if (polar_) polar_->Add(point);  // polar about the grid frame's origin: the reference pose
  }
  MarkFreeUpTo(nearest.cast<double>(), grid_T_vehicle);
}

// Every beam of the fan passed over the ground up to its nearest return: nothing there stands
// in the way (the popcount methods' free space; the slope method knows which returns are ground).
void StructureGridBuilder::MarkFreeUpTo(const Eigen::Vector2d& nearest, const Eigen::Isometry2d& grid_T_vehicle) {
  const double range = nearest.norm();
  if (range <= 0.0) return;
  const Eigen::Vector2d end = std::min(range, options_.free_space_range_m()) / range * nearest;
  grid_.MarkLine(grid_T_vehicle.translation(), grid_T_vehicle * end, CellClass::kFree);
}

CellClass StructureGridBuilder::ClassOfColumn(const VoxelColumn& column) const {
  if (column.empty()) return CellClass::kUnknown;
  const int count = std::popcount(column.bands & band_mask_);
  if (count >= options_.popcount().slammable_popcount()) return CellClass::kSlammable;
  if (count >= options_.popcount().hazard_popcount()) return CellClass::kHazard;
  return CellClass::kFree;
}

// Only the columns that hold returns: the others would mark nothing.
void StructureGridBuilder::ClassifyCartesianColumns() {
  const int width = grid_.geometry().width;
  for (const std::uint32_t offset : cartesian_->touched()) {
    const CellIndex cell{static_cast<int>(offset % static_cast<std::uint32_t>(width)),
                         static_cast<int>(offset / static_cast<std::uint32_t>(width))};
    grid_.Mark(cell, ClassOfColumn(cartesian_->columns()[offset]));
  }
}

void StructureGridBuilder::ClassifyPolarColumns() {
  for (const PolarBin& bin : polar_->touched()) {
    grid_.Mark(polar_->BinCenter(bin), ClassOfColumn(polar_->column(bin)));
  }
}

const ClassGrid& StructureGridBuilder::Finish() {
  if (cartesian_) ClassifyCartesianColumns();
  if (polar_) ClassifyPolarColumns();
  return grid_;
}

}  // namespace flat2d::maps
