#include "maps/grid/polar_voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flat2d::maps {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

PolarVoxelGrid::PolarVoxelGrid(const PolarGridLayout& layout, float band_height_m)
    : layout_(layout),
      band_height_m_(band_height_m),
      columns_(static_cast<std::size_t>(layout.azimuth_bins) * static_cast<std::size_t>(layout.range_bins)) {
  touched_.reserve(columns_.size());
  // Bin-centre directions once: Finish places every touched bin, tens of thousands a turn.
  directions_.reserve(static_cast<std::size_t>(layout.azimuth_bins));
  for (int a = 0; a < layout.azimuth_bins; ++a) {
    const double azimuth = (a + 0.5) * kTwoPi / layout.azimuth_bins;
    directions_.emplace_back(std::cos(azimuth), std::sin(azimuth));
  }
}

bool PolarVoxelGrid::Add(const Eigen::Vector3f& point) {
  const double x = static_cast<double>(point.x());
  const double y = static_cast<double>(point.y());
  return Add(std::atan2(y, x), std::hypot(x, y), point.z());
}

bool PolarVoxelGrid::Add(double azimuth_rad, double range_m, float z) {
  if (!std::isfinite(azimuth_rad) || !std::isfinite(z)) return false;
  const double range_bin = std::floor(range_m / layout_.range_resolution_m);
  if (!(range_bin >= 0.0 && range_bin < layout_.range_bins)) return false;
  double turns = azimuth_rad / kTwoPi;
  turns -= std::floor(turns);  // [0, 1)
  const int azimuth_bin =
      std::min(static_cast<int>(turns * layout_.azimuth_bins), layout_.azimuth_bins - 1);
  const PolarBin bin{azimuth_bin, static_cast<int>(range_bin)};
  VoxelColumn& column = columns_[Offset(bin)];
  if (column.empty()) touched_.push_back(bin);
  AddHeight(column, z, band_height_m_);
  return true;
}

void PolarVoxelGrid::Clear() {
  for (const PolarBin& bin : touched_) columns_[Offset(bin)] = VoxelColumn{};
  touched_.clear();
}

Eigen::Vector2d PolarVoxelGrid::BinCenter(const PolarBin& bin) const {
  const double range = (bin.range + 0.5) * layout_.range_resolution_m;
  return range * directions_[static_cast<std::size_t>(bin.azimuth)];
}

}  // namespace flat2d::maps
