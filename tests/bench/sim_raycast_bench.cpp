// Scene::Cast throughput for an HDL-32E sweep: 32 lasers from -30.67 to +10.67 deg
// elevation, 2170 azimuth steps (the sensor at 10 Hz fires ~69,000 rays a revolution, so
// 694,000 rays/s). The LiDAR simulator needs >= 5x real time on one core including packet
// encoding, so Cast must stay well under 200 ns/ray. Scenes: a synthetic campus generated
// here (a 1 km ring road with curbs and lanes, buildings, poles, trees with crowns,
// parked cars, fences and traffic), and the built-in `campus` world (worlds.hpp).
// Each iteration is one revolution from the next of 64 poses around the loop.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "hal/sim/scene.hpp"
#include "hal/sim/worlds.hpp"

namespace {

using namespace flat2d::hal::sim;

constexpr int kLasers = 32;
constexpr int kAzimuthSteps = 2170;
constexpr double kSensorHeightM = 1.9;
constexpr double kMaxRangeM = 100.0;

Vec2 P(double x, double y) {
  Vec2 p;
  p.set_x(x);
  p.set_y(y);
  return p;
}

// Centre line of the ring road: a 300 x 200 m rectangle (1 km), counter-clockwise.
Eigen::Vector2d RingPoint(double s) {
  s = std::fmod(s, 1000.0);
  if (s < 300) return {s, 0};
  if (s < 500) return {300, s - 300};
  if (s < 800) return {800 - s, 200};
  return {0, 1000 - s};
}

// Unit normal to the left (into the loop) at arc length s.
Eigen::Vector2d RingInward(double s) {
  s = std::fmod(s, 1000.0);
  if (s < 300) return {0, 1};
  if (s < 500) return {-1, 0};
  if (s < 800) return {0, -1};
  return {1, 0};
}

void AddRoad(SceneDescription& d) {
  for (const double offset : {-5.0, 5.0}) {  // curbs along both road edges
    Curb* curb = d.add_curbs();
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, {300.0, 0.0}, {300.0, 200.0}, {0.0, 200.0},
                               {0.0, 0.0}}) {
      *curb->add_points() = P(x + (x > 150 ? -offset : offset), y + (y > 100 ? -offset : offset));
    }
    curb->set_height_m(0.15);
    curb->set_width_m(0.3);
  }
  LaneMarking* centre = d.add_lanes();
  for (double s = 0; s <= 1000; s += 100) *centre->add_points() = P(RingPoint(s).x(), RingPoint(s).y());
  centre->set_width_m(0.15);
}

void AddRoadside(SceneDescription& d) {
  for (double s = 5; s < 1000; s += 5) {
    const Eigen::Vector2d c = RingPoint(s);
    const Eigen::Vector2d in = RingInward(s);
    const int k = static_cast<int>(s / 5);
    for (const double side : {-1.0, 1.0}) {
      if (k % 5 == 0) {  // poles every 25 m
        Cylinder* pole = d.add_cylinders();
        const Eigen::Vector2d at = c + side * in * 5.6;
        *pole->mutable_center() = P(at.x(), at.y());
        pole->set_radius_m(0.15);
        pole->set_height_m(8);
      }
      if (k % 3 == 1) {  // trees every 15 m: trunk and crown
        const Eigen::Vector2d t = c + side * in * 8.0;
        Cylinder* trunk = d.add_cylinders();
        *trunk->mutable_center() = P(t.x(), t.y());
        trunk->set_radius_m(0.2);
        trunk->set_height_m(3);
        Foliage* crown = d.add_foliage();
        *crown->mutable_center() = P(t.x(), t.y());
        crown->set_radius_m(2.5);
        crown->set_bottom(2.5);
        crown->set_top(7);
        crown->set_density_per_m(2);
      }
      if (side > 0 && k % 12 == 6) {  // parked cars on the inner side
        const Eigen::Vector2d car = c + in * 3.5;
        Box* box = d.add_boxes();
        *box->mutable_center() = P(car.x(), car.y());
        box->set_yaw(std::atan2(in.x(), -in.y()));
        box->set_length_m(4.5);
        box->set_width_m(1.8);
        box->set_height_m(1.5);
      }
    }
  }
}

void AddBuildingsAndFences(SceneDescription& d) {
  for (double s = 20; s < 1000; s += 40) {
    for (const double side : {-1.0, 1.0}) {
      const Eigen::Vector2d in = RingInward(s);
      const Eigen::Vector2d along(-in.y(), in.x());
      const Eigen::Vector2d near = RingPoint(s) + side * in * 14.0;
      const Eigen::Vector2d far = near + side * in * 15.0;
      ExtrudedPolygon* b = d.add_buildings();
      const Eigen::Vector2d side_step = along * 12.0;
      for (const Eigen::Vector2d& v : {Eigen::Vector2d(near - side_step), Eigen::Vector2d(near + side_step),
                                       Eigen::Vector2d(far + side_step), Eigen::Vector2d(far - side_step)}) {
        *b->add_vertices() = P(v.x(), v.y());
      }
      b->set_height_m(8 + std::fmod(s, 13.0));
      Bar* rail = d.add_bars();
      const Eigen::Vector2d f = RingPoint(s) + side * in * 11.0;
      *rail->mutable_a() = P((f - along * 15.0).x(), (f - along * 15.0).y());
      *rail->mutable_b() = P((f + along * 15.0).x(), (f + along * 15.0).y());
      rail->set_z(1.0);
      rail->set_thickness_m(0.06);
    }
  }
}

SceneDescription SyntheticCampus() {
  SceneDescription d;
  d.set_name("synthetic-campus");
  AddRoad(d);
  AddRoadside(d);
  AddBuildingsAndFences(d);
  for (int i = 0; i < 6; ++i) {  // traffic round the loop
    MovingObject* car = d.add_movers();
    car->mutable_box()->set_length_m(4.5);
    car->mutable_box()->set_width_m(1.8);
    car->mutable_box()->set_height_m(1.5);
    for (const auto& [x, y] : {std::pair{0.0, -2.0}, {302.0, -2.0}, {302.0, 202.0}, {-2.0, 202.0}}) {
      *car->add_path() = P(x, y);
    }
    car->set_speed_mps(10);
    car->set_start_s(-20.0 * i);
    car->set_loop(true);
  }
  return d;
}

std::vector<Eigen::Vector3d> SweepDirections() {
  std::vector<Eigen::Vector3d> directions;
  for (int a = 0; a < kAzimuthSteps; ++a) {
    const double azimuth = 2 * std::numbers::pi * a / kAzimuthSteps;
    for (int l = 0; l < kLasers; ++l) {
      const double elevation = (-30.67 + l * (41.34 / (kLasers - 1))) * std::numbers::pi / 180;
      directions.emplace_back(std::cos(elevation) * std::cos(azimuth),
                              std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
    }
  }
  return directions;
}

// One revolution per iteration from the next of `stations` (sensor XY positions).
void SweepScene(benchmark::State& state, const Scene& scene,
                const std::vector<Eigen::Vector2d>& stations) {
  const std::vector<Eigen::Vector3d> directions = SweepDirections();
  std::int64_t rays = 0;
  std::int64_t hits = 0;
  std::size_t station = 0;
  for (auto _ : state) {
    const Eigen::Vector2d xy = stations[station % stations.size()];
    const Eigen::Vector3d origin(xy.x(), xy.y(), scene.GroundHeight(xy.x(), xy.y()) + kSensorHeightM);
    // Each ray at its own time over the 0.1 s revolution, as the LiDAR simulator casts them.
    const double start = 0.1 * static_cast<double>(station);
    const double step = 0.1 / static_cast<double>(directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) {
      const auto hit = scene.Cast(origin, directions[i], kMaxRangeM, start + step * static_cast<double>(i));
      hits += hit ? 1 : 0;
    }
    rays += static_cast<std::int64_t>(directions.size());
    ++station;
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(rays);
  state.counters["ns_per_ray"] = benchmark::Counter(static_cast<double>(rays) * 1e-9,
                                                    benchmark::Counter::kIsRate |
                                                        benchmark::Counter::kInvert);
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(rays);
}

void BM_CastSyntheticCampus(benchmark::State& state) {
  const auto scene = Scene::Create(SyntheticCampus());
  if (!scene.ok()) {
    state.SkipWithError(scene.error().message.c_str());
    return;
  }
  std::vector<Eigen::Vector2d> stations;
  for (int i = 0; i < 64; ++i) {  // in the right-hand lane
    const double s = i * (1000.0 / 64) + 0.5;
    stations.push_back(RingPoint(s) - 2.0 * RingInward(s));
  }
  SweepScene(state, *scene, stations);
}
BENCHMARK(BM_CastSyntheticCampus)->Unit(benchmark::kMillisecond);

// state.range(0) = 0 drops the moving objects, to see what they cost.
void BM_CastBuiltInCampus(benchmark::State& state) {
  auto description = BuiltInWorld("campus");
  if (description.ok() && state.range(0) == 0) description->clear_movers();
  if (!description.ok()) {
    state.SkipWithError(description.error().message.c_str());
    return;
  }
  const auto scene = Scene::Create(*description);
  if (!scene.ok() || description->drives_size() == 0) {
    state.SkipWithError(scene.ok() ? "no drives" : scene.error().message.c_str());
    return;
  }
  std::vector<Eigen::Vector2d> stations;  // the mapping drive's waypoints
  for (const Vec2& w : description->drives(0).waypoints()) stations.emplace_back(w.x(), w.y());
  if (stations.empty()) {
    state.SkipWithError("the campus world has no mapping drive");
    return;
  }
  SweepScene(state, *scene, stations);
}
BENCHMARK(BM_CastBuiltInCampus)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
