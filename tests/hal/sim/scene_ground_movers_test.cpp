// Ramps (height, normal, slope, faces), moving objects at two times, and foliage
// (determinism, independence of call order, mean stop depth 1 / density).
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "hal/sim/scene.hpp"
#include "tests/hal/sim/scene_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::CastTowards;
using testing::MakeScene;

constexpr double kExactMetres = 1e-9;
const double kTan10 = std::tan(10.0 * std::numbers::pi / 180.0);

// A 10 deg ramp along +x from (0, 0): rise 0-10 m, plateau 10-15 m, fall 15-25 m, 4 m wide.
const char* kRampScene =
    "ground { height: 0.25 ramps { start { x: 0 y: 0 } heading: 0 run_m: 10 width_m: 4 "
    "slope_deg: 10 plateau_m: 5 descend: true } "
    "ramps { start { x: 0 y: 20 } heading: 0 run_m: 10 width_m: 4 slope_deg: 10 "
    "plateau_m: 5 } }";

TEST(SceneRampTest, HeightNormalAndSlopeAngle) {
  const Scene scene = MakeScene(kRampScene);
  EXPECT_NEAR(scene.GroundHeight(5, 0), 0.25 + 5 * kTan10, kExactMetres);
  EXPECT_NEAR(scene.GroundHeight(12, 1.9), 0.25 + 10 * kTan10, kExactMetres);
  EXPECT_NEAR(scene.GroundHeight(20, -1), 0.25 + 5 * kTan10, kExactMetres);
  EXPECT_NEAR(scene.GroundHeight(5, 2.1), 0.25, kExactMetres);   // beside it
  EXPECT_NEAR(scene.GroundHeight(-0.1, 0), 0.25, kExactMetres);  // before it
  const Eigen::Vector3d rise = scene.GroundNormal(5, 0);
  const Eigen::Vector3d fall = scene.GroundNormal(20, 0);
  EXPECT_NEAR(std::acos(rise.z()) * 180.0 / std::numbers::pi, 10.0, 1e-9);
  const double alpha = 10.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR((rise - Eigen::Vector3d(-std::sin(alpha), 0, std::cos(alpha))).norm(), 0.0, kExactMetres);
  EXPECT_NEAR(fall.x(), -rise.x(), kExactMetres);
  EXPECT_NEAR((scene.GroundNormal(12, 0) - Eigen::Vector3d::UnitZ()).norm(), 0.0, kExactMetres);
}

TEST(SceneRampTest, DescendingRampHeightIsContinuous) {
  const Scene scene = MakeScene(kRampScene);
  const double step = 1e-3;
  for (double u = -1.0; u < 26.0; u += step) {
    EXPECT_LE(std::abs(scene.GroundHeight(u + step, 0.5) - scene.GroundHeight(u, 0.5)),
              kTan10 * step + 1e-12)
        << "at u = " << u;
  }
}

TEST(SceneRampTest, CastHitsTheRampsFaces) {
  const Scene scene = MakeScene(kRampScene);
  // Straight down onto the rise.
  const auto down = CastTowards(scene, {5, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->range_m, 10 - 0.25 - 5 * kTan10, kExactMetres);
  EXPECT_NEAR((down->normal - scene.GroundNormal(5, 0)).norm(), 0.0, kExactMetres);
  EXPECT_EQ(down->kind, SurfaceKind::kGround);
  // Horizontal at 0.5 m from behind the start: meets the rise where the ramp is 0.25 m up.
  const auto level = CastTowards(scene, {-10, 0, 0.5}, {1, 0, 0});
  ASSERT_TRUE(level);
  EXPECT_NEAR(level->range_m, 10 + 0.25 / kTan10, kExactMetres);
  // The drop-off of the second ramp is a vertical face at u = 15.
  const auto drop = CastTowards(scene, {30, 20, 0.5}, {-1, 0, 0});
  ASSERT_TRUE(drop);
  EXPECT_NEAR(drop->range_m, 15.0, kExactMetres);
  EXPECT_NEAR((drop->normal - Eigen::Vector3d::UnitX()).norm(), 0.0, kExactMetres);
  // A side face (|v| = 2) where the ramp stands 5 tan(10) high.
  const auto side = CastTowards(scene, {5, -10, 0.3}, {0, 1, 0});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->range_m, 8.0, kExactMetres);
  EXPECT_NEAR((side->normal + Eigen::Vector3d::UnitY()).norm(), 0.0, kExactMetres);
}

TEST(SceneRampTest, TurnedRampFollowsItsHeading) {
  const Scene scene = MakeScene(
      "ground { ramps { start { x: 3 y: 4 } heading: 1.5707963267948966 run_m: 8 width_m: 3 "
      "slope_deg: 16 } }");
  const double tan16 = std::tan(16.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(scene.GroundHeight(3.5, 8), 4 * tan16, kExactMetres);
  EXPECT_NEAR(scene.GroundHeight(5.0, 8), 0.0, kExactMetres);  // |v| = 2 > 1.5
  EXPECT_NEAR(std::acos(scene.GroundNormal(3, 6).z()) * 180 / std::numbers::pi, 16.0, 1e-9);
  EXPECT_LT(scene.GroundNormal(3, 6).y(), 0.0);  // tilts back down the ramp
}

TEST(SceneMoverTest, BoxFollowsItsPathAtTwoTimes) {
  const Scene scene = MakeScene(
      "movers { box { length_m: 4 width_m: 2 height_m: 1.5 } path { x: 0 y: 10 } "
      "path { x: 100 y: 10 } speed_mps: 10 start_s: 1 }");
  // At t = 3 it has driven 20 m: centre (20, 10), its side at y = 9.
  const auto at3 = CastTowards(scene, {20, 0, 1}, {0, 1, 0}, 3.0);
  ASSERT_TRUE(at3);
  EXPECT_NEAR(at3->range_m, 9.0, kExactMetres);
  EXPECT_EQ(at3->kind, SurfaceKind::kMoving);
  EXPECT_FALSE(CastTowards(scene, {20, 0, 1}, {0, 1, 0}, 6.0).has_value());
  EXPECT_NEAR(CastTowards(scene, {50, 0, 1}, {0, 1, 0}, 6.0)->range_m, 9.0, kExactMetres);
  // Its rear face at x = 48 at t = 6, seen from behind.
  EXPECT_NEAR(CastTowards(scene, {0, 10, 1}, {1, 0, 0}, 6.0)->range_m, 48.0, kExactMetres);
  // Before its start time it waits at the start; after the end it stays there.
  EXPECT_NEAR(CastTowards(scene, {0, 0, 1}, {0, 1, 0}, -5.0)->range_m, 9.0, kExactMetres);
  EXPECT_NEAR(CastTowards(scene, {100, 0, 1}, {0, 1, 0}, 1e4)->range_m, 9.0, kExactMetres);
}

TEST(SceneMoverTest, YawFollowsThePathAndLoopsWrap) {
  const Scene scene = MakeScene(
      "movers { box { length_m: 4 width_m: 2 height_m: 1.5 } path { x: 0 y: 0 } "
      "path { x: 0 y: 100 } speed_mps: 10 } "
      "movers { cylinder { radius_m: 0.5 height_m: 1.8 } path { x: 50 y: 0 } "
      "path { x: 60 y: 0 } path { x: 60 y: 10 } path { x: 50 y: 10 } speed_mps: 1 loop: true }");
  // Heading north at t = 1: centre (0, 10), 4 m long along y, 2 m wide along x.
  EXPECT_NEAR(CastTowards(scene, {-10, 10, 1}, {1, 0, 0}, 1.0)->range_m, 9.0, kExactMetres);
  EXPECT_NEAR(CastTowards(scene, {0, 0, 1}, {0, 1, 0}, 1.0)->range_m, 8.0, kExactMetres);
  // The loop is 40 m (closed back to the first point): at t = 45 it is 5 m along, (55, 0).
  EXPECT_NEAR(CastTowards(scene, {55, -10, 1}, {0, 1, 0}, 45.0)->range_m, 9.5, kExactMetres);
  // At t = 35 it is on the closing edge (50, 10) -> (50, 0), at (50, 5).
  EXPECT_NEAR(CastTowards(scene, {40, 5, 1}, {1, 0, 0}, 35.0)->range_m, 9.5, kExactMetres);
}

TEST(SceneFoliageTest, DeterministicAndIndependentOfCallOrder) {
  const Scene scene = MakeScene(
      "foliage { center { x: 10 y: 0 } radius_m: 3 bottom: 0 top: 6 density_per_m: 2 }");
  const Eigen::Vector3d o(0, 0, 2);
  const Eigen::Vector3d a = Eigen::Vector3d(1, 0.05, 0).normalized();
  const Eigen::Vector3d b = Eigen::Vector3d(1, -0.05, 0).normalized();
  const auto first = scene.Cast(o, a, 100, 1.0);
  const auto other = scene.Cast(o, b, 100, 1.0);
  const auto again = scene.Cast(o, a, 100, 1.0);
  ASSERT_TRUE(first && other && again);
  EXPECT_EQ(first->range_m, again->range_m);
  EXPECT_EQ(first->kind, SurfaceKind::kFoliage);
  EXPECT_GE(first->range_m, 7.0 - 1e-9);  // not before the crown's edge
  EXPECT_NEAR((first->normal + a).norm(), 0.0, kExactMetres);
  const Scene rebuilt = MakeScene(
      "foliage { center { x: 10 y: 0 } radius_m: 3 bottom: 0 top: 6 density_per_m: 2 }");
  EXPECT_EQ(rebuilt.Cast(o, a, 100, 1.0)->range_m, first->range_m);
  int changed = 0;  // another time draws another depth
  for (int i = 0; i < 100; ++i) {
    changed += scene.Cast(o, a, 100, 1.0 + 0.01 * i)->range_m != first->range_m ? 1 : 0;
  }
  EXPECT_GE(changed, 95);
}

TEST(SceneFoliageTest, MeanStopDepthIsOneOverDensity) {
  // A huge crown, rays from outside it: depth = range - entry, exponential with mean 1/2 m.
  const Scene scene = MakeScene(
      "foliage { center { x: 0 y: 0 } radius_m: 100 bottom: 0 top: 400 density_per_m: 2 }");
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> height(100, 300);
  const int rays = 20000;
  double sum = 0.0;
  for (int i = 0; i < rays; ++i) {
    const double phi = angle(rng);
    const Eigen::Vector3d dir(std::cos(phi), std::sin(phi), 0.0);
    const Eigen::Vector3d origin = Eigen::Vector3d(0, 0, height(rng)) - 150.0 * dir;
    const auto hit = scene.Cast(origin, dir, 1000, 0.0);
    ASSERT_TRUE(hit);
    sum += hit->range_m - 50.0;  // the crown's edge is 50 m along
  }
  // Standard error of the mean: 0.5 / sqrt(20000) = 0.0035 m; allow 5 of them.
  EXPECT_NEAR(sum / rays, 0.5, 5 * 0.5 / std::sqrt(static_cast<double>(rays)));
}

}  // namespace
}  // namespace flat2d::hal::sim
