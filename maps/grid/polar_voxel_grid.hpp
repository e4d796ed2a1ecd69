// Polar compact voxel popcount grid (thesis 7.1.2): the same VoxelColumns binned by
// azimuth and horizontal range around the sensor instead of by x and y. A spinning LiDAR's
// fans already come in azimuth order, so a return is binned without projecting it to a
// Cartesian cell, and quantization error is only in range; bins grow with range, which
// is why the thesis pairs it with the Cartesian grid rather than replacing it.
//
// Bin (a, r) covers azimuths [a, a + 1) x 2 pi / azimuth_bins (counter-clockwise from x) and
// horizontal ranges [r, r + 1) x range_resolution_m. Sized once; Add and Clear allocate nothing.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "maps/grid/voxel_column.hpp"

namespace flat2d::maps {

struct PolarGridLayout {
  int azimuth_bins = 1800;  // 0.2 deg, about an HDL-32E firing step at 10 Hz
  int range_bins = 1000;
  double range_resolution_m = 0.05;

  double max_range_m() const { return range_bins * range_resolution_m; }
};

struct PolarBin {
  int azimuth = 0;
  int range = 0;
};

class PolarVoxelGrid {
 public:
  PolarVoxelGrid(const PolarGridLayout& layout, float band_height_m);

  // Adds a return given in the sensor-centred frame (x forward, z up); false when it is
  // beyond the last range bin or not finite.
  bool Add(const Eigen::Vector3f& point);
  // The same, for a return already known by azimuth (rad) and horizontal range.
  bool Add(double azimuth_rad, double range_m, float z);
  void Clear();

  const VoxelColumn& column(const PolarBin& bin) const { return columns_[Offset(bin)]; }
  bool IsStructure(const PolarBin& bin, int threshold, std::uint64_t band_mask = ~0ULL) const {
    return std::popcount(column(bin).bands & band_mask) >= threshold;
  }
  // The bin's centre in the sensor-centred frame, for drawing it into a Cartesian grid.
  Eigen::Vector2d BinCenter(const PolarBin& bin) const;

  const PolarGridLayout& layout() const { return layout_; }
  std::span<const VoxelColumn> columns() const { return columns_; }
  // Bins that hold returns, each once (as VoxelPopcountGrid::touched).
  std::span<const PolarBin> touched() const { return touched_; }

 private:
  std::size_t Offset(const PolarBin& bin) const {
    return static_cast<std::size_t>(bin.azimuth) * static_cast<std::size_t>(layout_.range_bins) +
           static_cast<std::size_t>(bin.range);
  }

  PolarGridLayout layout_;
  float band_height_m_;
  std::vector<VoxelColumn> columns_;  // azimuth-major: one azimuth's ranges are contiguous
  std::vector<PolarBin> touched_;     // capacity: every bin at most once
  std::vector<Eigen::Vector2d> directions_;  // unit vector to each azimuth bin's centre
};

}  // namespace flat2d::maps
