// The built-in worlds: each compiles into a Scene, has a mapping drive and localization
// drives that keep the vehicle clear of structure, and has the features its thesis
// experiment needs (sizes, slopes, heights, loop length).
#include "hal/sim/worlds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/sim/scene.hpp"
#include "hal/sim/trajectory.hpp"

namespace flat2d::hal::sim {
namespace {

using Point = Eigen::Vector2d;
constexpr double kClearanceM = 0.2;
constexpr double kVehicleHeightM = 2.0;

SceneDescription World(std::string_view name) {
  auto world = BuiltInWorld(name);
  EXPECT_TRUE(world.ok()) << name;
  return world.ok() ? *world : SceneDescription{};
}

Point P(const Vec2& v) { return {v.x(), v.y()}; }

// --- 2D geometry for the clearance check -------------------------------------------
double Cross(const Point& a, const Point& b) { return a.x() * b.y() - a.y() * b.x(); }

double PointSegment(const Point& p, const Point& a, const Point& b) {
  const Point ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool SegmentsCross(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

double SegmentSegment(const Point& a, const Point& b, const Point& c, const Point& d) {
  if (SegmentsCross(a, b, c, d)) return 0.0;
  return std::min({PointSegment(a, c, d), PointSegment(b, c, d), PointSegment(c, a, b),
                   PointSegment(d, a, b)});
}

bool Inside(const Point& p, const std::vector<Point>& polygon) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Point& a = polygon[i];
    const Point& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

// An obstacle as a closed polygon, an open polyline or a point, grown by `radius`.
struct Obstacle {
  Obstacle(std::vector<Point> points_in, bool closed_in, double radius_in, std::string what_in)
      : points(std::move(points_in)), closed(closed_in), radius(radius_in), what(std::move(what_in)) {
    for (const Point& p : points) bounds.extend(p);
  }
  std::vector<Point> points;
  bool closed = false;
  double radius = 0.0;
  std::string what;
  Eigen::AlignedBox2d bounds;
};

double Distance(const std::vector<Point>& body, const Obstacle& obstacle) {
  if (Inside(obstacle.points.front(), body)) return -obstacle.radius;
  if (obstacle.closed) {
    for (const Point& corner : body) {
      if (Inside(corner, obstacle.points)) return -obstacle.radius;
    }
  }
  double nearest = 1e9;
  const std::size_t n = obstacle.points.size();
  const std::size_t edges = n == 1 ? 1 : (obstacle.closed ? n : n - 1);
  for (std::size_t e = 0; e < edges; ++e) {
    const Point& a = obstacle.points[e];
    const Point& b = obstacle.points[(e + 1) % n];
    for (std::size_t k = 0; k < body.size(); ++k) {
      nearest = std::min(nearest, SegmentSegment(body[k], body[(k + 1) % body.size()], a, b));
    }
  }
  return nearest - obstacle.radius;
}

std::vector<Point> BoxCorners(const Point& c, double yaw, double length, double width) {
  const Point u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
  return {c + 0.5 * length * u + 0.5 * width * v, c - 0.5 * length * u + 0.5 * width * v,
          c - 0.5 * length * u - 0.5 * width * v, c + 0.5 * length * u - 0.5 * width * v};
}

template <typename Repeated>
std::vector<Point> Points(const Repeated& points) {
  std::vector<Point> out;
  for (const Vec2& p : points) out.push_back(P(p));
  return out;
}

// Everything static a vehicle body up to 2 m tall could touch.
std::vector<Obstacle> StaticObstacles(const SceneDescription& w) {
  std::vector<Obstacle> obstacles;
  for (int i = 0; i < w.walls_size(); ++i) {
    obstacles.push_back({Points(w.walls(i).points()), false, 0.5 * w.walls(i).thickness_m(), "walls[" + std::to_string(i) + "]"});
  }
  for (int i = 0; i < w.boxes_size(); ++i) {
    const Box& b = w.boxes(i);
    if (b.bottom() >= kVehicleHeightM) continue;
    obstacles.push_back({BoxCorners(P(b.center()), b.yaw(), b.length_m(), b.width_m()), true, 0.0, "boxes[" + std::to_string(i) + "]"});
  }
  for (int i = 0; i < w.buildings_size(); ++i) {
    obstacles.push_back({Points(w.buildings(i).vertices()), true, 0.0, "buildings[" + std::to_string(i) + "]"});
  }
  for (int i = 0; i < w.cylinders_size(); ++i) {
    obstacles.push_back({{P(w.cylinders(i).center())}, false, w.cylinders(i).radius_m(), "cylinders[" + std::to_string(i) + "]"});
  }
  for (int i = 0; i < w.bars_size(); ++i) {
    obstacles.push_back({{P(w.bars(i).a()), P(w.bars(i).b())}, false, 0.5 * w.bars(i).thickness_m(), "bars[" + std::to_string(i) + "]"});
  }
  for (int i = 0; i < w.curbs_size(); ++i) {
    // Segment by segment, so the bounding-box reject works on a kilometre of curb.
    const std::vector<Point> points = Points(w.curbs(i).points());
    for (std::size_t k = 1; k < points.size(); ++k) {
      obstacles.push_back({{points[k - 1], points[k]}, false, 0.5 * w.curbs(i).width_m(), "curbs[" + std::to_string(i) + "]"});
    }
  }
  for (int i = 0; i < w.foliage_size(); ++i) {
    if (w.foliage(i).bottom() >= kVehicleHeightM) continue;
    obstacles.push_back({{P(w.foliage(i).center())}, false, w.foliage(i).radius_m(), "foliage[" + std::to_string(i) + "]"});
  }
  return obstacles;
}

std::vector<Point> BodyOutline(const VehicleState& state, const VehicleGeometry& geometry) {
  const Eigen::AlignedBox2d box = VehicleFootprint(geometry);
  std::vector<Point> outline;
  for (const Point& corner : {box.min(), Point(box.max().x(), box.min().y()), box.max(),
                              Point(box.min().x(), box.max().y())}) {
    outline.push_back((state.world_T_vehicle * Eigen::Vector3d(corner.x(), corner.y(), 0.0)).head<2>());
  }
  return outline;
}

// The times to look at a drive: every `step` seconds to its end (and a second lap of a loop).
std::vector<double> SampleTimes(const Trajectory& trajectory, double step) {
  const double end = trajectory.duration_s() + trajectory.lap_duration_s();
  std::vector<double> times;
  for (double t = 0.0; t < end; t += step) times.push_back(t);
  times.push_back(end);
  return times;
}

// The smallest 2D distance from the body outline to any obstacle over the drive, and what.
std::pair<double, std::string> NearestStatic(const Trajectory& trajectory,
                                             const std::vector<Obstacle>& obstacles) {
  double nearest = 1e9;
  std::string nearest_what;
  for (const double t : SampleTimes(trajectory, 0.1)) {
    const std::vector<Point> body = BodyOutline(trajectory.At(t), trajectory.geometry());
    const Point centre = 0.25 * (body[0] + body[1] + body[2] + body[3]);
    for (const Obstacle& obstacle : obstacles) {
      // Cheap reject: the body lies within 3 m of its centre.
      if (obstacle.bounds.exteriorDistance(centre) > 3.0 + obstacle.radius) continue;
      const double d = Distance(body, obstacle);
      if (d < nearest) {
        nearest = d;
        nearest_what = obstacle.what + " at t=" + std::to_string(t);
      }
    }
  }
  return {nearest, nearest_what};
}

// --- tests ------------------------------------------------------------------------

TEST(WorldsTest, EveryWorldCompilesAndDrives) {
  ASSERT_EQ(BuiltInWorldNames().size(), 4u);
  for (const std::string_view name : BuiltInWorldNames()) {
    const SceneDescription world = World(name);
    EXPECT_EQ(world.name(), name);
    EXPECT_FALSE(world.description().empty());
    auto scene = Scene::Create(world);
    ASSERT_TRUE(scene.ok()) << name << ": " << scene.error().message;
    ASSERT_GE(world.drives_size(), 3) << name;
    EXPECT_EQ(world.drives(0).name(), "mapping") << name;
    std::set<std::string> names;
    for (const Drive& drive : world.drives()) {
      EXPECT_FALSE(drive.description().empty()) << name << "/" << drive.name();
      EXPECT_TRUE(names.insert(drive.name()).second) << name << ": repeated " << drive.name();
      auto trajectory = Trajectory::Create(*scene, drive);
      EXPECT_TRUE(trajectory.ok()) << name << ": " << trajectory.error().message;
    }
  }
}

TEST(WorldsTest, UnknownNameListsTheBuiltInWorlds) {
  auto world = BuiltInWorld("moon");
  ASSERT_FALSE(world.ok());
  EXPECT_NE(world.error().message.find("'moon'"), std::string::npos);
  EXPECT_NE(world.error().message.find("campus"), std::string::npos);
}

TEST(WorldsTest, WorldsAreDeterministic) {
  for (const std::string_view name : BuiltInWorldNames()) {
    EXPECT_EQ(World(name).SerializeAsString(), World(name).SerializeAsString()) << name;
  }
}

TEST(WorldsTest, OfficeIsA75By85FloorWithWideDoorsAndRobotSpeeds) {
  const SceneDescription world = World("office");
  auto scene = Scene::Create(world);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Eigen::Vector2d size = scene->bounds().sizes();
  EXPECT_NEAR(size.x(), 75.0, 1.0);
  EXPECT_NEAR(size.y(), 85.0, 1.0);
  bool has_loop = false;
  for (const Drive& drive : world.drives()) {
    EXPECT_GE(drive.speed_mps(), 1.0) << drive.name();
    EXPECT_LE(drive.speed_mps(), 1.5) << drive.name();
    has_loop |= drive.loop();
  }
  EXPECT_TRUE(has_loop);  // runs as long as a drift test wants
  // Doors: gaps between straight wall pieces on one line are 0 or at least 1.2 m.
  std::map<std::pair<int, long>, std::vector<std::pair<double, double>>> lines;
  for (const Wall& wall : world.walls()) {
    if (wall.points_size() != 2) continue;
    const Point a = P(wall.points(0)), b = P(wall.points(1));
    const bool vertical = a.x() == b.x();
    const long key = std::lround((vertical ? a.x() : a.y()) * 1000);
    const double lo = vertical ? std::min(a.y(), b.y()) : std::min(a.x(), b.x());
    const double hi = vertical ? std::max(a.y(), b.y()) : std::max(a.x(), b.x());
    lines[{vertical ? 1 : 0, key}].emplace_back(lo, hi);
  }
  int doors = 0;
  for (auto& [line, pieces] : lines) {
    std::sort(pieces.begin(), pieces.end());
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      const double gap = pieces[i].first - pieces[i - 1].second;
      if (gap > 1e-6) {
        EXPECT_GE(gap, 1.2);
        ++doors;
      }
    }
  }
  EXPECT_GE(doors, 40);
  EXPECT_GT(world.boxes_size(), 50);      // furniture
  EXPECT_GE(world.cylinders_size(), 9);   // pillars
}

TEST(WorldsTest, CampusLoopIsAtLeastOneKilometreWithTrafficAndStreetFurniture) {
  const SceneDescription world = World("campus");
  auto scene = Scene::Create(world);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  for (const Drive& drive : world.drives()) {
    auto trajectory = Trajectory::Create(*scene, drive);
    ASSERT_TRUE(trajectory.ok());
    EXPECT_GE(trajectory->path_length_m(), 1000.0) << drive.name();
  }
  EXPECT_GE(world.drives(0).speed_mps(), 8.0);
  EXPECT_LE(world.drives(0).speed_mps(), 10.0);
  int cars = 0, walkers = 0;
  for (const MovingObject& mover : world.movers()) {
    cars += mover.has_box();
    walkers += mover.has_cylinder();
    EXPECT_TRUE(mover.loop());
  }
  EXPECT_GE(cars, 6);
  EXPECT_GE(walkers, 4);
  EXPECT_EQ(world.curbs_size(), 2);
  EXPECT_GT(world.lanes_size(), 100);
  EXPECT_GE(world.buildings_size(), 10);
  EXPECT_GT(world.foliage_size(), 20);
  EXPECT_GE(world.bars_size(), 2);
  std::set<double> offsets;
  for (const Drive& drive : world.drives()) offsets.insert(drive.world_time_offset_s());
  EXPECT_EQ(offsets.size(), static_cast<std::size_t>(world.drives_size()));
}

TEST(WorldsTest, RampsHaveTheThesisSlopesAndOneDriveClimbsTheTenDegreeRamp) {
  const SceneDescription world = World("ramps");
  auto scene = Scene::Create(world);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  std::vector<double> measured;
  for (const Ramp& ramp : world.ground().ramps()) {
    // The slope as the scene's ground sees it, between 1 m and 4 m up the ramp.
    const Point along(std::cos(ramp.heading()), std::sin(ramp.heading()));
    const Point a = P(ramp.start()) + 1.0 * along, b = P(ramp.start()) + 4.0 * along;
    const double rise = scene->GroundHeight(b.x(), b.y()) - scene->GroundHeight(a.x(), a.y());
    measured.push_back(std::atan2(rise, 3.0) * 180.0 / std::numbers::pi);
  }
  std::sort(measured.begin(), measured.end());
  ASSERT_EQ(measured.size(), 3u);
  EXPECT_NEAR(measured[0], 10.0, 0.01);
  EXPECT_NEAR(measured[1], 14.5, 0.01);
  EXPECT_NEAR(measured[2], 16.0, 0.01);
  double steepest_pitch = 0.0;
  for (const Drive& drive : world.drives()) {
    auto trajectory = Trajectory::Create(*scene, drive);
    ASSERT_TRUE(trajectory.ok());
    for (const double t : SampleTimes(*trajectory, 0.05)) {
      const double pitch = std::asin(trajectory->At(t).world_T_vehicle.linear()(2, 0));
      steepest_pitch = std::max(steepest_pitch, pitch * 180.0 / std::numbers::pi);
    }
  }
  EXPECT_NEAR(steepest_pitch, 10.0, 0.5);
}

TEST(WorldsTest, OccluderHeightsAscendFromTenCentimetresToOneMetre) {
  const SceneDescription world = World("occluders");
  std::vector<std::pair<double, double>> row;  // (x, height) of the boxes on the row's axis
  for (const Box& box : world.boxes()) {
    if (std::abs(box.center().y()) < 1e-9) row.emplace_back(box.center().x(), box.height_m());
  }
  std::sort(row.begin(), row.end());
  ASSERT_EQ(row.size(), 10u);
  for (std::size_t i = 0; i < row.size(); ++i) {
    EXPECT_NEAR(row[i].second, 0.1 * static_cast<double>(i + 1), 1e-12);
    if (i > 0) {
      EXPECT_NEAR(row[i].first - row[i - 1].first, row[1].first - row[0].first, 1e-9);
    }
  }
}

class DriveClearanceTest : public ::testing::TestWithParam<std::string_view> {};

// The body outline stays 0.2 m off every static primitive (2D, exact), and points on the
// outline 0.5 m up stay 0.2 m off every surface the scene knows, moving traffic included.
TEST(WorldsTest, ClearanceCheckSeesACollision) {
  SceneDescription world = World("occluders");
  Drive* through = world.add_drives();
  through->set_name("through-the-row");
  for (const double x : {-10.0, 24.0}) {
    Vec2* w = through->add_waypoints();
    w->set_x(x);
    w->set_y(0.0);
  }
  through->set_speed_mps(1.0);
  auto trajectory = Trajectory::Create([](double, double) { return 0.0; }, *through);
  ASSERT_TRUE(trajectory.ok());
  const auto [nearest, what] = NearestStatic(*trajectory, StaticObstacles(world));
  EXPECT_LE(nearest, 0.0) << what;
  EXPECT_EQ(what.rfind("boxes[", 0), 0u) << what;
  // Beside the row, 1.2 m off its side (2 m wide): 0.2 m from the body's side.
  through->mutable_waypoints(0)->set_y(2.1);
  through->mutable_waypoints(1)->set_y(2.1);
  through->mutable_waypoints(1)->set_x(20.0);
  auto beside = Trajectory::Create([](double, double) { return 0.0; }, *through);
  ASSERT_TRUE(beside.ok());
  EXPECT_NEAR(NearestStatic(*beside, StaticObstacles(world)).first, 0.2, 1e-9);
}

TEST_P(DriveClearanceTest, VehicleStaysClear) {
  const SceneDescription world = World(GetParam());
  auto scene = Scene::Create(world);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const std::vector<Obstacle> obstacles = StaticObstacles(world);
  for (const Drive& drive : world.drives()) {
    auto trajectory = Trajectory::Create(*scene, drive);
    ASSERT_TRUE(trajectory.ok()) << trajectory.error().message;
    const VehicleGeometry& geometry = trajectory->geometry();
    const auto [nearest, nearest_what] = NearestStatic(*trajectory, obstacles);
    std::printf("%s/%s: nearest static structure %.2f m (%s)\n", world.name().c_str(),
                drive.name().c_str(), nearest, nearest_what.c_str());
    EXPECT_GT(nearest, kClearanceM) << drive.name() << ": " << nearest_what;

    const Eigen::AlignedBox2d box = VehicleFootprint(geometry);
    double nearest_surface = 1e9;
    for (const double t : SampleTimes(*trajectory, 0.5)) {
      const VehicleState state = trajectory->At(t);
      for (double x = box.min().x(); x <= box.max().x() + 1e-9; x += box.sizes().x() / 2) {
        for (const double y : {box.min().y(), box.max().y()}) {  // corners and mid-sides
          const Eigen::Vector3d point = state.world_T_vehicle * Eigen::Vector3d(x, y, 0.5);
          nearest_surface = std::min(
              nearest_surface, scene->DistanceToSurface(point, t + drive.world_time_offset_s()));
        }
      }
    }
    std::printf("%s/%s: nearest surface 0.5 m up %.2f m\n", world.name().c_str(),
                drive.name().c_str(), nearest_surface);
    EXPECT_GT(nearest_surface, kClearanceM) << drive.name();
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, DriveClearanceTest,
                         ::testing::Values("office", "campus", "ramps", "occluders"),
                         [](const auto& param_info) { return std::string(param_info.param); });

}  // namespace
}  // namespace flat2d::hal::sim
