// The scan to be matched: 2D points in the vehicle frame, in fixed storage.
//
// Sources: the structure cells of a local grid whose frame is the vehicle's (AddGridCells,
// what the daemon's structure grid produces each revolution), a 2D laser scan given as
// ranges at evenly spaced bearings (AddLaserScan), or single points (Add). The matcher's
// cost is linear in the point count, and neighbouring points of a dense scan say almost the
// same thing, so VoxelDecimate keeps one point (the centroid) per voxel: a few thousand
// structure points of a Velodyne revolution become several hundred. Non-finite points are
// rejected on entry and counted, so the matcher never sees them from here.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "localization/matching/match_grid.hpp"

namespace flat2d::localization {

class ScanPoints {
 public:
  explicit ScanPoints(std::size_t max_points);

  void Clear();
  // Appends `p`; false (and counted in rejected()) when non-finite or when full.
  bool Add(const Eigen::Vector2d& p);
  // Appends a point per finite range in [min_range, max_range] at bearing
  // angle_min + i * angle_increment (sensor frame = vehicle frame); returns how many.
  std::size_t AddLaserScan(std::span<const float> ranges, double angle_min,
                           double angle_increment, double min_range, double max_range);
  // Appends the centre of each structure cell of `local_grid` (a grid in the vehicle frame).
  std::size_t AddGridCells(const MatchGrid& local_grid);
  // Replaces the points by the centroid of those in each voxel_size square; allocates
  // nothing. Order afterwards is by voxel, not by input.
  void VoxelDecimate(double voxel_size);

  std::span<const Eigen::Vector2d> points() const { return points_; }
  std::size_t size() const { return points_.size(); }
  std::size_t capacity() const { return capacity_; }
  std::uint64_t rejected() const { return rejected_; }

 private:
  std::size_t capacity_ = 0;
  std::vector<Eigen::Vector2d> points_;                      // capacity_
  std::vector<Eigen::Vector2d> scratch_;                     // capacity_, VoxelDecimate's output
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys_;  // capacity_, voxel key, index
  std::uint64_t rejected_ = 0;
};

}  // namespace flat2d::localization
