// The grid walk against a brute-force reference on random clutter, hit points on the
// surfaces (DistanceToSurface ~ 0), no allocation in Cast, and validation errors.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "hal/sim/scene.hpp"
#include "hal/sim/scene_compile.hpp"
#include "tests/hal/sim/scene_test_support.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::MakeScene;
using testing::ParseScene;

Vec2 Point(double x, double y) {
  Vec2 p;
  p.set_x(x);
  p.set_y(y);
  return p;
}

// x drawn before y. As two arguments of one call the draws would have no order, and each
// compiler would make another scene from the same seed.
Vec2 RandomPoint(std::uniform_real_distribution<double>& xy, std::mt19937& rng) {
  const double x = xy(rng);
  return Point(x, xy(rng));
}

// 60 x 60 m of every primitive kind at random, seeded.
SceneDescription RandomClutter(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-30, 30);
  std::uniform_real_distribution<double> size(0.2, 4);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  SceneDescription d;
  d.mutable_ground()->set_height(0.1);
  for (int i = 0; i < 4; ++i) {
    Ramp* r = d.mutable_ground()->add_ramps();
    *r->mutable_start() = RandomPoint(xy, rng);
    r->set_heading(angle(rng));
    r->set_run_m(size(rng) * 2);
    r->set_width_m(size(rng) + 1);
    r->set_slope_deg(5 + 5 * i);
    r->set_plateau_m(size(rng));
    r->set_descend(i % 2 == 0);
  }
  for (int i = 0; i < 40; ++i) {
    Box* b = d.add_boxes();
    *b->mutable_center() = RandomPoint(xy, rng);
    b->set_yaw(angle(rng));
    b->set_length_m(size(rng));
    b->set_width_m(size(rng));
    b->set_height_m(size(rng));
    b->set_bottom(i % 5 == 0 ? size(rng) : 0.0);
    Cylinder* c = d.add_cylinders();
    *c->mutable_center() = RandomPoint(xy, rng);
    c->set_radius_m(0.1 * size(rng));
    c->set_height_m(2 * size(rng));
  }
  for (int i = 0; i < 8; ++i) {
    const double x = xy(rng);
    const double y = xy(rng);
    const double s = size(rng);
    ExtrudedPolygon* p = d.add_buildings();  // an L, concave
    for (const auto& [u, v] : {std::pair{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0},
                               {1.0, 2.0}, {0.0, 2.0}}) {
      *p->add_vertices() = Point(x + s * u, y + s * v);
    }
    p->set_height_m(3 * size(rng));
    Wall* w = d.add_walls();
    *w->add_points() = RandomPoint(xy, rng);
    *w->add_points() = RandomPoint(xy, rng);
    *w->add_points() = RandomPoint(xy, rng);
    w->set_thickness_m(0.2);
    w->set_height_m(2.5);
    Bar* bar = d.add_bars();
    *bar->mutable_a() = RandomPoint(xy, rng);
    *bar->mutable_b() = RandomPoint(xy, rng);
    bar->set_z(1.0);
    bar->set_thickness_m(0.08);
    Curb* curb = d.add_curbs();
    *curb->add_points() = RandomPoint(xy, rng);
    *curb->add_points() = RandomPoint(xy, rng);
    curb->set_height_m(0.15);
    curb->set_width_m(0.3);
    Foliage* f = d.add_foliage();
    *f->mutable_center() = RandomPoint(xy, rng);
    f->set_radius_m(size(rng));
    f->set_bottom(1.5);
    f->set_top(5);
    f->set_density_per_m(1.5);
  }
  MovingObject* m = d.add_movers();
  m->mutable_box()->set_length_m(4.5);
  m->mutable_box()->set_width_m(1.8);
  m->mutable_box()->set_height_m(1.5);
  *m->add_path() = Point(-30, -2);
  *m->add_path() = Point(30, 2);
  m->set_speed_mps(8);
  return d;
}

struct RandomRay {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
};

std::vector<RandomRay> RandomRays(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-35, 35);
  std::uniform_real_distribution<double> z(0.3, 4);
  std::uniform_real_distribution<double> azimuth(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> elevation(-0.6, 0.3);
  std::vector<RandomRay> rays;
  for (int i = 0; i < count; ++i) {
    const double a = azimuth(rng);
    const double e = i % 50 == 0 ? -std::numbers::pi / 2 : elevation(rng);  // some vertical
    // Braces: the draws are made in order (a call's arguments have none).
    rays.push_back({Eigen::Vector3d{xy(rng), xy(rng), z(rng)},
                    Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                    std::sin(e))});
  }
  return rays;
}

// Every solid tested for every ray: what the grid must reproduce.
std::optional<double> BruteForceRange(const internal::CompiledStatics& s, const RandomRay& r,
                                      double max_range, double time_s) {
  const internal::Ray ray{r.origin, r.direction};
  double best = max_range;
  const auto offer = [&](const std::optional<internal::PrimitiveHit>& hit) {
    if (hit && hit->t < best) best = hit->t;
  };
  if (r.direction.z() != 0.0) {
    const double t = (s.ground_height - r.origin.z()) / r.direction.z();
    if (t >= 0.0) offer(internal::PrimitiveHit{t, Eigen::Vector3d::UnitZ()});
  }
  for (const auto& b : s.boxes) offer(internal::Intersect(b, ray, best));
  for (const auto& c : s.cylinders) offer(internal::Intersect(c, ray, best));
  for (const auto& p : s.prisms) offer(internal::IntersectPrism(p, s.prism_vertices.data(), ray, best));
  for (const auto& f : s.foliage) offer(internal::IntersectFoliage(f, ray, best, time_s));
  for (const auto& ramp : s.ramps) offer(internal::Intersect(ramp.solid, ray, best));
  for (const auto& m : s.movers) offer(m.Intersect(ray, best, time_s));
  if (best >= max_range) return std::nullopt;
  return best;
}

TEST(SceneConsistencyTest, GridWalkMatchesBruteForce) {
  for (const std::uint32_t seed : {1U, 2U, 3U}) {
    const SceneDescription d = RandomClutter(seed);
    const Result<Scene> scene = Scene::Create(d);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const internal::CompiledStatics statics = internal::CompileScene(d);
    int hits = 0;
    for (const RandomRay& ray : RandomRays(3000, seed + 100)) {
      const double time = 2.0;
      const auto expected = BruteForceRange(statics, ray, 80.0, time);
      const auto actual = scene->Cast(ray.origin, ray.direction, 80.0, time);
      ASSERT_EQ(expected.has_value(), actual.has_value())
          << "seed " << seed << " origin " << ray.origin.transpose() << " dir "
          << ray.direction.transpose();
      if (!expected) continue;
      ++hits;
      EXPECT_NEAR(actual->range_m, *expected, 1e-9) << "seed " << seed;
    }
    EXPECT_GT(hits, 2250) << "seed " << seed;  // most rays hit something
  }
}

TEST(SceneConsistencyTest, HitPointsLieOnSurfaces) {
  const Result<Scene> scene = Scene::Create(RandomClutter(7));
  ASSERT_TRUE(scene.ok());
  double worst = 0.0;
  for (const RandomRay& ray : RandomRays(2000, 8)) {
    const auto hit = scene->Cast(ray.origin, ray.direction, 80.0, 1.5);
    if (!hit) continue;
    const Eigen::Vector3d p = ray.origin + hit->range_m * ray.direction;
    worst = std::max(worst, scene->DistanceToSurface(p, 1.5));
    EXPECT_LE(hit->normal.dot(ray.direction), 1e-12);  // faces the origin
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(SceneConsistencyTest, DistanceToSurfaceOfKnownPoints) {
  const Scene scene = MakeScene(
      "boxes { center { x: 10 y: 0 } length_m: 2 width_m: 2 height_m: 3 } "
      "foliage { center { x: -10 y: 0 } radius_m: 2 bottom: 1 top: 4 density_per_m: 1 }");
  EXPECT_NEAR(scene.DistanceToSurface({0, 0, 5}, 0), 5.0, 1e-12);     // above the ground
  EXPECT_NEAR(scene.DistanceToSurface({8, 0, 1}, 0), 1.0, 1e-12);     // before the box face
  EXPECT_NEAR(scene.DistanceToSurface({10, 0, 2.5}, 0), 0.5, 1e-12);  // inside, under its top
  EXPECT_NEAR(scene.DistanceToSurface({12, 2, 4}, 0), std::sqrt(3.0), 1e-12);  // corner
  EXPECT_EQ(scene.DistanceToSurface({-10, 0.5, 2}, 0), 0.0);          // inside the foliage
}

TEST(SceneConsistencyTest, CastAllocatesNothing) {
  const Result<Scene> scene = Scene::Create(RandomClutter(11));
  ASSERT_TRUE(scene.ok());
  const std::vector<RandomRay> rays = RandomRays(5000, 12);
  double sum = 0.0;
  const std::uint64_t before = flat2d::testing::AllocationCount();
  for (const RandomRay& ray : rays) {
    const auto hit = scene->Cast(ray.origin, ray.direction, 80.0, 3.0);
    sum += hit ? hit->range_m : 0.0;
  }
  EXPECT_EQ(flat2d::testing::AllocationCount(), before);
  EXPECT_GT(sum, 0.0);
}

struct BadScene {
  const char* text;
  const char* error;
};

TEST(SceneValidationTest, ErrorsNameTheElement) {
  const BadScene cases[] = {
      {"boxes {} boxes { length_m: 1 width_m: 1 height_m: 0 }", "boxes[0].length_m: must be positive"},
      {"boxes { length_m: 1 width_m: 1 height_m: 1 } boxes { length_m: 1 width_m: 1 height_m: -2 }",
       "boxes[1].height_m: must be positive and finite"},
      {"walls { points { x: 0 } thickness_m: 0.2 height_m: 2 }", "walls[0].points: needs at least 2"},
      {"walls { points { x: 0 } points { x: 0 } thickness_m: 0.2 height_m: 2 }",
       "walls[0].points[1]: repeats the previous point"},
      {"buildings { vertices { x: 0 y: 0 } vertices { x: 2 y: 2 } vertices { x: 2 y: 0 } "
       "vertices { x: 0 y: 1 } height_m: 3 }",
       "buildings[0].vertices: edges 0 and 2 cross"},
      {"buildings { vertices { x: 0 } vertices { x: 1 } vertices { x: 2 } height_m: 3 }",
       "buildings[0].vertices: polygon has no area"},
      {"cylinders { radius_m: nan height_m: 1 }", "cylinders[0].radius_m"},
      {"bars { a { x: 1 } b { x: 1 } thickness_m: 0.1 }", "bars[0]: a and b coincide"},
      {"curbs { points { x: 0 } points { x: 1 } height_m: 0.1 width_m: 0 }", "curbs[0].width_m"},
      {"foliage { radius_m: 1 bottom: 3 top: 2 density_per_m: 1 }", "foliage[0].top: must be above"},
      {"ground { ramps { run_m: 1 width_m: 1 slope_deg: 45 } }", "ground.ramps[0].slope_deg"},
      {"ground { height: inf }", "ground.height: must be finite"},
      {"lanes { points { x: 0 } points { x: 1 } width_m: 0.1 reflectivity: 256 }",
       "lanes[0].reflectivity: must be at most 255"},
      {"movers { path { x: 0 } speed_mps: 1 }", "movers[0]: needs a shape"},
      {"movers { box { length_m: 1 width_m: 1 height_m: 1 } speed_mps: 1 }",
       "movers[0].path: needs at least 1 points"},
      {"movers { cylinder { radius_m: 1 height_m: 1 } path { x: 0 } speed_mps: -1 }",
       "movers[0].speed_mps"},
      {"drives { waypoints { x: nan } }", "drives[0].waypoints[0].x: must be finite"},
  };
  for (const BadScene& c : cases) {
    const Result<Scene> scene = Scene::Create(ParseScene(c.text));
    ASSERT_FALSE(scene.ok()) << c.text;
    EXPECT_NE(scene.error().message.find(c.error), std::string::npos)
        << "got: " << scene.error().message << "\nwanted: " << c.error;
  }
  EXPECT_TRUE(Scene::Create(ParseScene("")).ok());  // an empty world is flat ground
}

}  // namespace
}  // namespace flat2d::hal::sim
