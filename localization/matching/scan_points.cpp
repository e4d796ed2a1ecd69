#include "localization/matching/scan_points.hpp"

#include <algorithm>
#include <cmath>

namespace flat2d::localization {
namespace {

// A voxel index packed into 64 bits; coordinates are finite and bounded by then, and the
// offset keeps both halves non-negative for any point within +-2^31 voxels.
std::uint64_t VoxelKey(const Eigen::Vector2d& p, double voxel_size) {
  constexpr double kOffset = 2147483648.0;
  const auto index = [voxel_size](double v) {
    const double cell = std::clamp(std::floor(v / voxel_size), -kOffset, kOffset - 1.0);
    return static_cast<std::uint64_t>(cell + kOffset);
  };
  const std::uint64_t ix = index(p.x());
  const std::uint64_t iy = index(p.y());
  return (ix << 32) | (iy & 0xffffffffULL);
}

}  // namespace

ScanPoints::ScanPoints(std::size_t max_points) : capacity_(max_points) {
  points_.reserve(capacity_);
  scratch_.reserve(capacity_);
  keys_.reserve(capacity_);
}

void ScanPoints::Clear() {
  points_.clear();
  rejected_ = 0;
}

bool ScanPoints::Add(const Eigen::Vector2d& p) {
  if (!p.allFinite() || points_.size() >= capacity_) {
    ++rejected_;
    return false;
  }
  points_.push_back(p);
  return true;
}

std::size_t ScanPoints::AddLaserScan(std::span<const float> ranges, double angle_min,
                                     double angle_increment, double min_range,
                                     double max_range) {
  std::size_t added = 0;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const double range = static_cast<double>(ranges[i]);
    if (!(range >= min_range && range <= max_range)) continue;  // also drops NaN
    const double bearing = angle_min + static_cast<double>(i) * angle_increment;
    if (Add(Eigen::Vector2d(range * std::cos(bearing), range * std::sin(bearing)))) ++added;
  }
  return added;
}

std::size_t ScanPoints::AddGridCells(const MatchGrid& local_grid) {
  std::size_t added = 0;
  for (int y = 0; y < local_grid.height(); ++y) {
    for (int x = 0; x < local_grid.width(); ++x) {
      if (local_grid.Occupied(x, y) && Add(local_grid.geometry().CellCenter(x, y))) ++added;
    }
  }
  return added;
}

void ScanPoints::VoxelDecimate(double voxel_size) {
  if (!(voxel_size > 0.0) || points_.empty()) return;
  keys_.clear();
  for (std::size_t i = 0; i < points_.size(); ++i) {
    keys_.emplace_back(VoxelKey(points_[i], voxel_size), static_cast<std::uint32_t>(i));
  }
  std::sort(keys_.begin(), keys_.end());
  scratch_.clear();
  for (std::size_t begin = 0; begin < keys_.size();) {
    std::size_t end = begin;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (; end < keys_.size() && keys_[end].first == keys_[begin].first; ++end) {
      sum += points_[keys_[end].second];
    }
    scratch_.push_back(sum / static_cast<double>(end - begin));
    begin = end;
  }
  points_.swap(scratch_);
}

}  // namespace flat2d::localization
