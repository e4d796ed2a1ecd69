// Scene::Cast against hand-computed geometry for every primitive kind (exact to 1e-9 m),
// normals facing the origin, nearest of several, range limit, inside/grazing/parallel rays,
// reflectivity defaults and lane markings.
#include "hal/sim/scene.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hal/sim/scene_compile.hpp"
#include "tests/hal/sim/scene_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::CastTowards;
using testing::MakeScene;

constexpr double kExact = 1e-9;  // metres; the intersections are closed-form

void ExpectHit(const std::optional<SurfaceHit>& hit, double range, const Eigen::Vector3d& normal,
               SurfaceKind kind = SurfaceKind::kStatic) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->range_m, range, kExact);
  EXPECT_NEAR((hit->normal - normal.normalized()).norm(), 0.0, kExact)
      << "normal " << hit->normal.transpose() << " expected " << normal.normalized().transpose();
  EXPECT_EQ(hit->kind, kind);
}

TEST(SceneCastTest, GroundPlaneAtItsBaseHeight) {
  const Scene scene = MakeScene("ground { height: -0.5 }");
  // From 2 m up at 45 deg down: the plane at z = -0.5 is 2.5 m below, 2.5 sqrt(2) along.
  ExpectHit(CastTowards(scene, {0, 0, 2}, {1, 0, -1}), 2.5 * std::sqrt(2.0), {0, 0, 1},
            SurfaceKind::kGround);
  EXPECT_FALSE(CastTowards(scene, {0, 0, 2}, {1, 0, 0}).has_value());  // parallel, no hit
  EXPECT_FALSE(CastTowards(scene, {0, 0, 2}, {1, 0, 0.1}).has_value());
  EXPECT_EQ(CastTowards(scene, {0, 0, 2}, {0, 0, -1})->reflectivity,
            internal::kDefaultGroundReflectivity);
}

TEST(SceneCastTest, AxisAlignedBox) {
  const Scene scene = MakeScene(
      "boxes { center { x: 10 y: 0 } length_m: 2 width_m: 2 height_m: 3 reflectivity: 77 }");
  const auto hit = CastTowards(scene, {0, 0, 1}, {1, 0, 0});
  ExpectHit(hit, 9.0, {-1, 0, 0});
  EXPECT_EQ(hit->reflectivity, 77);
  ExpectHit(CastTowards(scene, {10, 0, 10}, {0, 0, -1}), 7.0, {0, 0, 1});  // top face
  // Horizontal at 3.5 m: passes over the 3 m top and never meets the ground.
  EXPECT_EQ(CastTowards(scene, {0, 0, 3.5}, {1, 0, 0}), std::nullopt);
}

TEST(SceneCastTest, TurnedBoxFaceAndNormal) {
  // Yaw 45 deg: the face whose outward normal is (-1, -1)/sqrt2 has its centre at
  // c - (1, 1)/sqrt2; a ray 5 m back along that normal hits it at range 5.
  const Scene scene = MakeScene(
      "boxes { center { x: 10 y: 0 } yaw: 0.7853981633974483 length_m: 2 width_m: 2 "
      "height_m: 3 }");
  const double s = std::sqrt(0.5);
  const Eigen::Vector3d face_centre(10 - s, -s, 1);
  ExpectHit(CastTowards(scene, face_centre - 5 * Eigen::Vector3d(s, s, 0), {1, 1, 0}), 5.0,
            {-1, -1, 0});
}

TEST(SceneCastTest, WallSegmentsCloseTheirCornersButKeepFreeEnds) {
  const Scene scene = MakeScene(
      "walls { points { x: 0 y: 0 } points { x: 10 y: 0 } points { x: 10 y: 10 } "
      "thickness_m: 0.2 height_m: 2 }");
  ExpectHit(CastTowards(scene, {5, -5, 1}, {0, 1, 0}), 4.9, {0, -1, 0});
  ExpectHit(CastTowards(scene, {-3, 0, 1}, {1, 0, 0}), 3.0, {-1, 0, 0});  // free end at x = 0
  // The outer corner is closed: the first segment reaches x = 10.1.
  ExpectHit(CastTowards(scene, {15, -0.05, 1}, {-1, 0, 0}), 4.9, {1, 0, 0});
  ExpectHit(CastTowards(scene, {10.05, -5, 1}, {0, 1, 0}), 4.9, {0, -1, 0});
}

TEST(SceneCastTest, ConcaveBuildingSidesAndCaps) {
  // An L: the notch is x in [4, 10], y in [4, 10].
  const Scene scene = MakeScene(
      "buildings { vertices { x: 0 y: 0 } vertices { x: 10 y: 0 } vertices { x: 10 y: 4 } "
      "vertices { x: 4 y: 4 } vertices { x: 4 y: 10 } vertices { x: 0 y: 10 } height_m: 6 "
      "bottom: 1 }");
  ExpectHit(CastTowards(scene, {8, 8, 2}, {-1, 0, 0}), 4.0, {1, 0, 0});
  ExpectHit(CastTowards(scene, {8, 8, 2}, {0, -1, 0}), 4.0, {0, 1, 0});
  ExpectHit(CastTowards(scene, {2, 2, 10}, {0, 0, -1}), 3.0, {0, 0, 1});   // roof at z = 7
  ExpectHit(CastTowards(scene, {2, 2, 0.5}, {0, 0, 1}), 0.5, {0, 0, -1});  // underside z = 1
  // Under the raised bottom the ray passes beneath.
  EXPECT_FALSE(CastTowards(scene, {-5, 2, 0.5}, {1, 0, 0}).has_value());
  // From inside: the exit face, normal towards the origin.
  ExpectHit(CastTowards(scene, {2, 2, 2}, {1, 0, 0}), 8.0, {-1, 0, 0});
}

TEST(SceneCastTest, CylinderSideAndCapExactly) {
  const Scene scene = MakeScene(
      "cylinders { center { x: 10 y: 0 } radius_m: 1 height_m: 3 bottom: 0 }");
  ExpectHit(CastTowards(scene, {0, 0, 1}, {1, 0, 0}), 9.0, {-1, 0, 0});
  const double x = std::sqrt(0.75);  // off-centre by 0.5: enters at x = 10 - sqrt(0.75)
  ExpectHit(CastTowards(scene, {0, 0.5, 1}, {1, 0, 0}), 10.0 - x, {-x, 0.5, 0});
  ExpectHit(CastTowards(scene, {10.3, 0.2, 10}, {0, 0, -1}), 7.0, {0, 0, 1});
  ExpectHit(CastTowards(scene, {10, 0, 1}, {0, 1, 0}), 1.0, {0, -1, 0});  // from inside
  // Grazing: a hair outside the radius misses, a hair inside hits.
  EXPECT_FALSE(CastTowards(scene, {0, 1.0 + 1e-9, 1}, {1, 0, 0}).has_value());
  EXPECT_TRUE(CastTowards(scene, {0, 1.0 - 1e-6, 1}, {1, 0, 0}).has_value());
}

TEST(SceneCastTest, BarAndCurb) {
  const Scene scene = MakeScene(
      "bars { a { x: 0 y: 5 } b { x: 10 y: 5 } z: 1 thickness_m: 0.1 } "
      "curbs { points { x: 0 y: 3 } points { x: 10 y: 3 } height_m: 0.15 width_m: 0.3 }");
  ExpectHit(CastTowards(scene, {5, 0, 1}, {0, 1, 0}), 4.95, {0, -1, 0});
  EXPECT_FALSE(CastTowards(scene, {5, 0, 1.06}, {0, 1, 0}).has_value());  // above the rail
  ExpectHit(CastTowards(scene, {5, 0, 0.1}, {0, 1, 0}), 2.85, {0, -1, 0});
  ExpectHit(CastTowards(scene, {5, 3, 1}, {0, 0, -1}), 0.85, {0, 0, 1});  // curb top
  EXPECT_EQ(CastTowards(scene, {5, 0, 0.1}, {0, 1, 0})->reflectivity,
            internal::kDefaultCurbReflectivity);
}

TEST(SceneCastTest, NearestOfSeveralWhateverTheOrder) {
  for (const bool box_first : {true, false}) {
    const std::string box = "boxes { center { x: 10 y: 0 } length_m: 1 width_m: 1 height_m: 2 } ";
    const std::string cyl = "cylinders { center { x: 20 y: 0 } radius_m: 1 height_m: 5 } ";
    const Scene scene = MakeScene(box_first ? box + cyl : cyl + box);
    ExpectHit(CastTowards(scene, {0, 0, 1}, {1, 0, 0}), 9.5, {-1, 0, 0});
    ExpectHit(CastTowards(scene, {0, 0, 3}, {1, 0, 0}), 19.0, {-1, 0, 0});
    ExpectHit(CastTowards(scene, {30, 0, 1}, {-1, 0, 0}), 9.0, {1, 0, 0});
  }
}

TEST(SceneCastTest, MaximumRangeIsRespected) {
  const Scene scene = MakeScene("boxes { center { x: 10 y: 0 } length_m: 2 width_m: 2 height_m: 3 }");
  EXPECT_FALSE(CastTowards(scene, {0, 0, 1}, {1, 0, 0}, 0.0, 8.99).has_value());
  ExpectHit(CastTowards(scene, {0, 0, 1}, {1, 0, 0}, 0.0, 9.01), 9.0, {-1, 0, 0});
  EXPECT_FALSE(CastTowards(scene, {0, 0, 100}, {0, 0, -1}, 0.0, 50.0).has_value());
}

TEST(SceneCastTest, ParallelToAFaceJustOutsideMisses) {
  const Scene scene = MakeScene("boxes { center { x: 10 y: 0 } length_m: 2 width_m: 2 height_m: 3 }");
  EXPECT_FALSE(CastTowards(scene, {0, 1.0 + 1e-9, 1}, {1, 0, 0}).has_value());
  EXPECT_FALSE(CastTowards(scene, {0, 0, 3.0 + 1e-9}, {1, 0, 0}).has_value());
  EXPECT_TRUE(CastTowards(scene, {0, 1.0 - 1e-9, 1}, {1, 0, 0}).has_value());
}

TEST(SceneCastTest, LaneMarkingsChangeOnlyTheGroundsReflectivity) {
  const Scene scene = MakeScene(
      "ground { reflectivity: 9 } "
      "lanes { points { x: 0 y: 0 } points { x: 50 y: 0 } width_m: 0.2 reflectivity: 150 } "
      "boxes { center { x: 20 y: 0 } length_m: 1 width_m: 1 height_m: 1 reflectivity: 33 }");
  EXPECT_EQ(CastTowards(scene, {10, 0.09, 2}, {0, 0, -1})->reflectivity, 150);
  EXPECT_EQ(CastTowards(scene, {10, 0.11, 2}, {0, 0, -1})->reflectivity, 9);
  EXPECT_EQ(CastTowards(scene, {60, 0.0, 2}, {0, 0, -1})->reflectivity, 9);  // past the end
  EXPECT_EQ(CastTowards(scene, {20, 0.0, 2}, {0, 0, -1})->reflectivity, 33);  // box on a lane
  // Slanted ray landing on the line 10 m away.
  const auto hit = CastTowards(scene, {0, 0, 2}, {10, 0, -2});
  EXPECT_EQ(hit->reflectivity, 150);
  EXPECT_EQ(hit->kind, SurfaceKind::kGround);
}

TEST(SceneCastTest, BoundsHoldPrimitivesLanesAndWaypoints) {
  const Scene scene = MakeScene(
      "cylinders { center { x: 10 y: 0 } radius_m: 1 height_m: 3 } "
      "lanes { points { x: -20 y: 0 } points { x: 0 y: 0 } width_m: 0.2 } "
      "drives { waypoints { x: 0 y: 40 } waypoints { x: 1 y: 40 } }");
  const Eigen::AlignedBox2d b = scene.bounds();
  EXPECT_NEAR(b.min().x(), -20.1, kExact);  // the lane's half width
  EXPECT_NEAR(b.max().x(), 11.0, kExact);
  EXPECT_NEAR(b.min().y(), -1.0, kExact);
  EXPECT_NEAR(b.max().y(), 40.0, kExact);
}

}  // namespace
}  // namespace flat2d::hal::sim
