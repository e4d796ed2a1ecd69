// Many revolutions' structure grids merged into one grid in a world frame (`flat2d-grid
// --poses`, and the prior-map builder's input): each revolution votes, so structure seen
// once by mistake or by a passing car does not stay.
//
// Steps: every observed cell of a revolution's grid is carried to the world cell holding its
// centre through world_T_grid and counts one observation of its class there. Finally a cell
// is slammable when at least `min_structure_fraction` of its observations (and at least
// `min_structure_votes`) said slammable, hazard when that much said hazard or slammable,
// free when observed at all, unknown otherwise. The world grid is sized once.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "maps/grid/class_grid.hpp"

namespace flat2d::maps {

struct AccumulationOptions {
  double min_structure_fraction = 0.3;
  int min_structure_votes = 2;
};

class GridAccumulator {
 public:
  GridAccumulator(const GridGeometry& world, const AccumulationOptions& options = {});

  // Adds one revolution's grid, whose frame is at world_T_grid.
  void Add(const ClassGrid& grid, const Eigen::Isometry2d& world_T_grid);
  // The voted classes.
  ClassGrid Result() const;

  const GridGeometry& geometry() const { return geometry_; }
  int revolutions() const { return revolutions_; }

 private:
  struct Votes {
    std::uint16_t observed = 0;
    std::uint16_t hazard = 0;     // hazard or slammable
    std::uint16_t slammable = 0;
  };

  GridGeometry geometry_;
  AccumulationOptions options_;
  std::vector<Votes> votes_;
  int revolutions_ = 0;
};

// The world grid that holds every pose of a drive plus `margin_m` around it (the sensor's
// useful range), at `resolution_m`.
GridGeometry GeometryAround(const std::vector<Eigen::Vector2d>& positions, double margin_m, double resolution_m);

}  // namespace flat2d::maps
