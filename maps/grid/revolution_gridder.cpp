#include "maps/grid/revolution_gridder.hpp"

#include <utility>

namespace flat2d::maps {

Result<RevolutionGridder> RevolutionGridder::Create(const hal::velodyne::LaserTable& table,
                                                    const StructureGridOptions& options,
                                                    const VehiclePoseSource* poses, double cut_azimuth_rad) {
  auto first = StructureGridBuilder::Create(table, options);
  if (!first.ok()) return first.error();
  auto second = StructureGridBuilder::Create(table, options);
  if (!second.ok()) return second.error();
  return RevolutionGridder(std::move(*first), std::move(*second), poses, cut_azimuth_rad);
}

RevolutionGridder::RevolutionGridder(StructureGridBuilder first, StructureGridBuilder second,
                                     const VehiclePoseSource* poses, double cut_azimuth_rad)
    : builders_{std::move(first), std::move(second)}, poses_(poses), cut_(cut_azimuth_rad) {}

void RevolutionGridder::StartRevolution(const hal::velodyne::Fan& fan) {
  PublishedGrid& grid = grids_[static_cast<std::size_t>(filling_)];
  grid = PublishedGrid{};
  grid.start_ns = fan.stamp_ns;
  if (poses_ != nullptr) {
    if (const auto pose = poses_->PoseAt(fan.stamp_ns)) grid.local_T_grid = *pose;
  }
  grid_T_local_ = grid.local_T_grid.inverse();
  builders_[static_cast<std::size_t>(filling_)].Begin();
  started_ = true;
}

void RevolutionGridder::AddFan(const hal::velodyne::Fan& fan) {
  PublishedGrid& grid = grids_[static_cast<std::size_t>(filling_)];
  Eigen::Isometry2d grid_T_vehicle = Eigen::Isometry2d::Identity();
  if (poses_ != nullptr) {
    if (const auto local_T_vehicle = poses_->PoseAt(fan.stamp_ns)) {
      grid_T_vehicle = grid_T_local_ * *local_T_vehicle;
    } else {
      ++grid.fans_without_pose;
    }
  }
  builders_[static_cast<std::size_t>(filling_)].AddFan(fan, grid_T_vehicle);
  grid.end_ns = fan.stamp_ns;
  ++grid.fans;
}

const PublishedGrid* RevolutionGridder::Add(std::span<const hal::velodyne::Fan> fans) {
  const PublishedGrid* completed = nullptr;
  for (const hal::velodyne::Fan& fan : fans) {
    if (cut_.Next(fan.azimuth_rad).wraps && started_) {
      completed = Publish(started_at_cut_);
      started_at_cut_ = true;
    }
    if (!started_) StartRevolution(fan);
    AddFan(fan);
  }
  return completed;
}

const PublishedGrid* RevolutionGridder::Flush() {
  if (!started_) return nullptr;
  const PublishedGrid* partial = Publish(false);
  started_at_cut_ = false;
  cut_.Reset();
  return partial;
}

const PublishedGrid* RevolutionGridder::Publish(bool complete) {
  const auto index = static_cast<std::size_t>(filling_);
  PublishedGrid& grid = grids_[index];
  grid.grid = &builders_[index].Finish();
  grid.complete = complete;
  grid.sequence = next_sequence_++;
  filling_ = 1 - filling_;
  started_ = false;
  return &grid;
}

}  // namespace flat2d::maps
