#include "tests/localization/matching/synthetic_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace flat2d::localization::testing {
namespace {

// Distance along the ray (origin, direction) to the segment, or infinity.
double RayHit(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, const Segment& s) {
  const Eigen::Vector2d edge = s.b - s.a;
  const double denominator = direction.x() * edge.y() - direction.y() * edge.x();
  if (std::abs(denominator) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d to_a = s.a - origin;
  const double t = (to_a.x() * edge.y() - to_a.y() * edge.x()) / denominator;
  const double u = (to_a.x() * direction.y() - to_a.y() * direction.x()) / denominator;
  if (t <= 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

double SegmentDistance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d edge = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
  return (s.a + t * edge - p).norm();
}

}  // namespace

void World::AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if (walls.empty()) {
    min = a.cwiseMin(b);
    max = a.cwiseMax(b);
  }
  walls.push_back({a, b});
  min = min.cwiseMin(a).cwiseMin(b);
  max = max.cwiseMax(a).cwiseMax(b);
}

void World::AddBox(const Eigen::Vector2d& corner, const Eigen::Vector2d& size) {
  const Eigen::Vector2d c1 = corner + Eigen::Vector2d(size.x(), 0.0);
  const Eigen::Vector2d c2 = corner + size;
  const Eigen::Vector2d c3 = corner + Eigen::Vector2d(0.0, size.y());
  AddWall(corner, c1);
  AddWall(c1, c2);
  AddWall(c2, c3);
  AddWall(c3, corner);
}

double World::Clearance(const Eigen::Vector2d& p) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Segment& wall : walls) nearest = std::min(nearest, SegmentDistance(p, wall));
  return nearest;
}

World RoomsWorld() {
  World world;
  world.AddBox({0.0, 0.0}, {20.0, 14.0});
  // Interior walls with doorways (gaps of 1-1.5 m).
  world.AddWall({8.0, 0.0}, {8.0, 5.0});
  world.AddWall({8.0, 6.2}, {8.0, 14.0});
  world.AddWall({0.0, 7.0}, {3.5, 7.0});
  world.AddWall({5.0, 7.0}, {8.0, 7.0});
  world.AddWall({8.0, 9.0}, {14.0, 9.0});
  world.AddWall({15.5, 9.0}, {20.0, 9.0});
  world.AddWall({13.0, 0.0}, {13.0, 4.0});
  // Furniture that breaks the symmetry of the rooms.
  world.AddBox({2.0, 2.0}, {1.2, 0.6});
  world.AddBox({5.5, 10.5}, {0.8, 1.6});
  world.AddBox({10.0, 3.0}, {1.5, 1.5});
  world.AddBox({16.5, 11.0}, {2.0, 0.8});
  world.AddBox({17.0, 2.5}, {0.5, 3.0});
  world.AddWall({10.0, 12.0}, {12.0, 13.0});
  return world;
}

World CorridorWorld(double length, double width) {
  World world;
  world.AddWall({-0.5 * length, -0.5 * width}, {0.5 * length, -0.5 * width});
  world.AddWall({-0.5 * length, 0.5 * width}, {0.5 * length, 0.5 * width});
  return world;
}

World CornerWorld(double length) {
  World world;
  world.AddWall({0.0, 0.0}, {length, 0.0});
  world.AddWall({0.0, 0.0}, {0.0, length});
  return world;
}

World OutdoorWorld(double size, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> along(0.0, size);
  std::uniform_real_distribution<double> corner(0.0, size - 25.0);
  std::uniform_real_distribution<double> building(6.0, 25.0);
  World world;
  world.AddBox({0.0, 0.0}, {size, size});  // the block's boundary walls and fences
  for (int i = 0; i < 25; ++i) {  // buildings
    // Braces and the corner first: the draws are made in order (a call's arguments have none).
    const Eigen::Vector2d at{corner(random), corner(random)};
    world.AddBox(at, {building(random), building(random)});
  }
  std::uniform_real_distribution<double> fence(5.0, 30.0);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  for (int i = 0; i < 20; ++i) {  // fences and kerbs
    const Eigen::Vector2d a{along(random), along(random)};
    const double heading = angle(random);
    const Eigen::Vector2d b =
        a + fence(random) * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    world.AddWall(a, b.cwiseMax(0.0).cwiseMin(size));
  }
  for (int i = 0; i < 300; ++i) {  // poles, trunks, posts
    const Eigen::Vector2d pole{along(random), along(random)};
    world.AddBox(pole.cwiseMin(size - 0.3), {0.3, 0.3});
  }
  return world;
}

MatchGrid Rasterize(const World& world, double resolution, double margin) {
  GridGeometry geometry;
  geometry.resolution = resolution;
  // Half a cell off, so that the worlds' walls on round coordinates run through cell
  // centres: on cell borders, every wall would be rasterized half a cell to one side, a
  // bias that real maps (walls anywhere within cells) do not have.
  geometry.origin = world.min - Eigen::Vector2d::Constant(margin + 0.5 * resolution);
  const Eigen::Vector2d extent = world.max - world.min + Eigen::Vector2d::Constant(2.0 * margin);
  geometry.width = static_cast<int>(std::ceil(extent.x() / resolution));
  geometry.height = static_cast<int>(std::ceil(extent.y() / resolution));
  MatchGrid grid(geometry);
  for (const Segment& wall : world.walls) {
    const double length = (wall.b - wall.a).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.25 * resolution))));
    for (int i = 0; i <= steps; ++i) {
      grid.MarkPoint(wall.a + (wall.b - wall.a) * (static_cast<double>(i) / steps));
    }
  }
  return grid;
}

std::vector<Eigen::Vector2d> CastScan(const World& world, const Se2& map_T_vehicle,
                                      const LaserModel& laser, std::mt19937* noise) {
  std::vector<Eigen::Vector2d> points;
  std::normal_distribution<double> range_noise(0.0, laser.noise_sigma);
  const bool full_circle = laser.fov >= 2.0 * std::numbers::pi - 1e-9;
  const double increment = laser.fov / (full_circle ? laser.beams : laser.beams - 1);
  for (int i = 0; i < laser.beams; ++i) {
    const double bearing = -0.5 * laser.fov + i * increment;
    const Eigen::Vector2d direction_vehicle(std::cos(bearing), std::sin(bearing));
    const Eigen::Vector2d direction = map_T_vehicle.Rotation() * direction_vehicle;
    double range = std::numeric_limits<double>::infinity();
    for (const Segment& wall : world.walls) {
      range = std::min(range, RayHit(map_T_vehicle.translation(), direction, wall));
    }
    if (range > laser.max_range) continue;
    if (noise != nullptr && laser.noise_sigma > 0.0) range += range_noise(*noise);
    points.push_back(range * direction_vehicle);
  }
  return points;
}

Se2 RandomFreePose(const World& world, double clearance, std::mt19937& random) {
  std::uniform_real_distribution<double> x(world.min.x(), world.max.x());
  std::uniform_real_distribution<double> y(world.min.y(), world.max.y());
  std::uniform_real_distribution<double> theta(-std::numbers::pi, std::numbers::pi);
  while (true) {
    const Eigen::Vector2d p{x(random), y(random)};
    if (world.Clearance(p) >= clearance) return Se2(p, theta(random));
  }
}

}  // namespace flat2d::localization::testing
