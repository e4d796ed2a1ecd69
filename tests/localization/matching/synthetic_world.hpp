// Synthetic 2D worlds for matcher tests and benchmarks: walls as line segments,
// rasterized into a MatchGrid and seen by an exact ray-casting laser, so that the true
// pose of every simulated scan is known.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "localization/matching/match_grid.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::testing {

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

struct World {
  std::vector<Segment> walls;
  Eigen::Vector2d min = Eigen::Vector2d::Zero();  // bounding box of the walls
  Eigen::Vector2d max = Eigen::Vector2d::Zero();

  void AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  void AddBox(const Eigen::Vector2d& corner, const Eigen::Vector2d& size);
  // Distance from `p` to the nearest wall.
  double Clearance(const Eigen::Vector2d& p) const;
};

// Rooms with doorways and furniture boxes, about 20 x 14 m.
World RoomsWorld();
// Two parallel walls `length` long, `width` apart, along x, centred at the origin.
World CorridorWorld(double length, double width);
// Two walls meeting at a right angle at the origin, along +x and +y.
World CornerWorld(double length);
// An outdoor block: buildings, fences and poles over size x size metres (seeded).
World OutdoorWorld(double size, std::uint32_t seed);

// The walls rasterized at `resolution` with `margin` metres around them.
MatchGrid Rasterize(const World& world, double resolution, double margin);

struct LaserModel {
  int beams = 360;
  double fov = 2.0 * 3.141592653589793;  // centred on the vehicle's x axis
  double max_range = 20.0;
  double noise_sigma = 0.0;  // metres, along the beam
};

// Points (vehicle frame) where the beams from map_T_vehicle hit the nearest wall.
std::vector<Eigen::Vector2d> CastScan(const World& world, const Se2& map_T_vehicle,
                                      const LaserModel& laser, std::mt19937* noise = nullptr);

// A pose uniformly inside the world's box with at least `clearance` metres to any wall.
Se2 RandomFreePose(const World& world, double clearance, std::mt19937& random);

}  // namespace flat2d::localization::testing
