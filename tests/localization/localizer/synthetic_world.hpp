// A walled yard for the localizer's tests: its class grid written as a prior map file, a
// truth drive round it, each revolution's structure grid (what the map holds within range
// of the vehicle, in the vehicle frame: no occlusion, which the matcher does not need), and
// odometry that drifts (scale and yaw-rate bias) as a MEMS-grade vehicle's would.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "hal/common/time.hpp"
#include "localization/odometry/odometry_sample.hpp"
#include "localization/odometry/se2.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/revolution_gridder.hpp"

namespace flat2d::testing {

inline constexpr TimeNs kRevolutionNs = 100 * kNsPerMs;  // 10 Hz
inline constexpr TimeNs kOdometryNs = 10 * kNsPerMs;     // 100 Hz

class SyntheticWorld {
 public:
  // The yard (60 x 50 m, walls, pillars and a few inner walls, none symmetric), its map file
  // written to `map_path`.
  SyntheticWorld(const std::filesystem::path& map_path, double duration_s);

  // The truth: anticlockwise laps of a rounded rectangle at 5 m/s, from t = 0.
  localization::Se2 TruthAt(TimeNs t) const;
  // Dead reckoning of the truth with a speed scale of 1.01 and a yaw-rate bias of
  // 0.005 rad/s, in a local frame that starts at the identity at t = 0; every kOdometryNs
  // up to the duration given at construction.
  const localization::OdometrySample& OdometryAt(TimeNs t) const;

  // Revolution k's grid (starting at k * kRevolutionNs) into `grid` (preallocated, see
  // MakeScanGrid; nothing is allocated), and its PublishedGrid; `empty` leaves it without
  // structure (a blinded sensor).
  maps::PublishedGrid Revolution(int k, maps::ClassGrid& grid, bool empty = false) const;
  static maps::ClassGrid MakeScanGrid();

  const std::vector<Eigen::Vector2d>& structure() const { return structure_; }

 private:
  std::vector<Eigen::Vector2d> structure_;  // slammable cell centres, map frame
  std::vector<localization::OdometrySample> odometry_;  // one per kOdometryNs from 0
};

}  // namespace flat2d::testing
