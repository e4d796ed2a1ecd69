// How fast the vehicle goes along a DrivePath: the classic forward-backward pass over a
// table of nodes every ~5 cm of arc length.
//
// Steps: (1) each node's speed cap is min(cruise, sqrt(a_lat / |kappa|)) with kappa the
// largest curvature within one node spacing, so v^2 * kappa <= a_lat holds everywhere
// between nodes too; (2) a forward pass limits acceleration, v[i+1]^2 <= v[i]^2 + 2 a ds,
// and a backward pass limits braking the same way; an open drive starts and ends at rest;
// (3) between nodes v^2 is linear in s, i.e. constant acceleration, so the time of each
// interval is exact (2 ds / (v[i] + v[i+1])) and position and speed are continuous in
// time. A loop has two tables: the periodic lap (both passes run cyclically, started
// from the node with the lowest cap, which no pass can change) and the first lap from
// rest, min(periodic, sqrt(2 a s)), which joins the periodic speed before the lap ends.
#pragma once

#include <string_view>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/sim/drive_path.hpp"

namespace flat2d::hal::sim {

struct SpeedLimits {
  double cruise_mps = 0.0;
  double max_accel_mps2 = 1.0;
  double max_lateral_accel_mps2 = 2.0;
};

// Where the vehicle is along the path at a time: s grows without bound on a loop (lap
// after lap); DrivePath::At wraps it.
struct PathMotion {
  double s = 0.0;
  double speed_mps = 0.0;
  double accel_mps2 = 0.0;
};

class SpeedProfile {
 public:
  static Result<SpeedProfile> Create(const DrivePath& path, const SpeedLimits& limits,
                                     std::string_view drive_name);

  // Clamped to [0, duration_s()] for an open path; a loop keeps going. Allocates nothing.
  PathMotion At(double drive_time_s) const;

  // Time to the end of an open path, or of the first lap of a loop.
  double duration_s() const { return first_.duration_s(); }
  // Time of each further lap of a loop (0 for an open path).
  double lap_duration_s() const { return periodic_.duration_s(); }
  double node_spacing_m() const { return spacing_m_; }

 private:
  // Speeds at nodes i * spacing and the time each node is reached.
  struct Table {
    std::vector<double> speed;
    std::vector<double> time;
    double duration_s() const { return time.empty() ? 0.0 : time.back(); }
  };

  SpeedProfile() = default;
  void FillTimes(Table& table) const;
  PathMotion Interpolate(const Table& table, double t) const;

  Table first_;
  Table periodic_;  // empty for an open path
  double spacing_m_ = 0.0;
  double length_m_ = 0.0;
};

}  // namespace flat2d::hal::sim
