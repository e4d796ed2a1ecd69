#include "maps/grid/slope_classifier.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kSensorHeight = 1.9;

// A fan of `lasers` returns from a sensor at kSensorHeight looking along +x at elevations
// from -25 to -1 deg, hitting the terrain `height(x)` (found by marching the ray).
template <typename Terrain>
std::vector<Eigen::Vector3f> FanOver(Terrain height, int lasers = 16) {
  std::vector<Eigen::Vector3f> returns;
  for (int i = 0; i < lasers; ++i) {
    const double elevation = (-25.0 + 24.0 * i / (lasers - 1)) * kDeg;
    for (double t = 0.0; t < 60.0; t += 0.001) {
      const double x = t * std::cos(elevation);
      const double z = kSensorHeight + t * std::sin(elevation);
      if (z <= height(x)) {
        returns.emplace_back(static_cast<float>(x), 0.0f, static_cast<float>(z));
        break;
      }
    }
  }
  return returns;  // bottom-up by construction: elevations ascend
}

std::vector<CellClass> Classify(const std::vector<Eigen::Vector3f>& returns,
                                const SlopeThresholds& thresholds = {}) {
  std::vector<CellClass> classes(returns.size());
  ClassifyFan(returns, thresholds, classes);
  return classes;
}

TEST(ProfileSlope, TwoPointsGiveTheirAngle) {
  const std::vector<Eigen::Vector2d> level{{1, 0}, {2, 0}};
  const std::vector<Eigen::Vector2d> ramp{{1, 0}, {2, std::tan(14.5 * kDeg)}};
  const std::vector<Eigen::Vector2d> wall{{5, 0.2}, {5, 1.0}};
  const std::vector<Eigen::Vector2d> down{{1, 0}, {2, -std::tan(30 * kDeg)}};
  EXPECT_NEAR(ProfileSlope(level), 0.0, 1e-12);
  EXPECT_NEAR(ProfileSlope(ramp), 14.5 * kDeg, 1e-12);
  EXPECT_NEAR(ProfileSlope(wall), 90.0 * kDeg, 1e-12);
  EXPECT_NEAR(ProfileSlope(down), 30.0 * kDeg, 1e-12);
}

TEST(ProfileSlope, ThreePointFitSmoothsNoise) {
  // Collinear on a 10 deg line with the middle point 2 cm off: the pairwise slopes swing,
  // the fit stays near 10 deg.
  const double t = std::tan(10 * kDeg);
  const std::vector<Eigen::Vector2d> profile{{4.0, 4.0 * t}, {4.3, 4.3 * t + 0.02}, {4.6, 4.6 * t}};
  EXPECT_NEAR(ProfileSlope(profile), 10 * kDeg, 0.5 * kDeg);
  EXPECT_GT(std::abs(ProfileSlope(std::span(profile).first(2)) - 10 * kDeg), 3 * kDeg);
}

TEST(ClassifyFan, FlatGroundIsFree) {
  const auto classes = Classify(FanOver([](double) { return 0.0; }));
  for (CellClass c : classes) EXPECT_EQ(c, CellClass::kFree);
}

TEST(ClassifyFan, WallIsSlammableAtItsFace) {
  const auto returns = FanOver([](double x) { return x >= 8.0 ? 10.0 : 0.0; });
  const auto classes = Classify(returns);
  std::size_t first_on_wall = 0;
  while (returns[first_on_wall].x() < 7.99f) ++first_on_wall;
  ASSERT_GE(first_on_wall, 2u);
  ASSERT_LE(first_on_wall + 3, returns.size());
  // Ground returns are free except the last one: the step onto the wall is marked on the
  // return nearer the vehicle (conservative marking).
  for (std::size_t i = 0; i + 1 < first_on_wall; ++i) EXPECT_EQ(classes[i], CellClass::kFree) << i;
  EXPECT_NE(classes[first_on_wall - 1], CellClass::kFree);
  // Consecutive wall returns are vertical pairs: of each pair the nearer return is marked
  // slammable; the farther one of both its pairs (same cell, mm apart) stays unknown.
  for (std::size_t i = first_on_wall; i + 1 < returns.size(); ++i) {
    EXPECT_TRUE(classes[i] == CellClass::kSlammable || classes[i + 1] == CellClass::kSlammable) << i;
    EXPECT_TRUE(classes[i] == CellClass::kSlammable || classes[i] == CellClass::kUnknown) << i;
  }
}

// A fence 8 m out: bars 5 cm thick at 0.45 m and 1.2 m, the ground seen between and behind.
TEST(ClassifyFan, SeeThroughFenceIsSlammableOnlyWithTheSeeThroughRule) {
  auto fence = [](double x) { return 0.0 * x; };
  std::vector<Eigen::Vector3f> returns = FanOver(fence, 32);
  // Replace the returns whose rays cross x = 8 at a bar's height by returns on that bar.
  std::size_t on_bars = 0;
  for (Eigen::Vector3f& r : returns) {
    const double elevation = std::atan2(static_cast<double>(r.z()) - kSensorHeight, static_cast<double>(r.x()));
    const double z_at_fence = kSensorHeight + 8.0 * std::tan(elevation);
    for (const double bar : {0.45, 1.2}) {
      if (r.x() > 8.0f && std::abs(z_at_fence - bar) < 0.025) {
        r = Eigen::Vector3f(8.0f, 0.0f, static_cast<float>(z_at_fence));
        ++on_bars;
      }
    }
  }
  ASSERT_GE(on_bars, 2u) << "the fan must hit both bars";
  auto slammable = [&](const SlopeThresholds& thresholds) {
    std::size_t n = 0;
    for (const CellClass c : Classify(returns, thresholds)) n += c == CellClass::kSlammable;
    return n;
  };
  EXPECT_EQ(slammable({}), 0u) << "consecutive pairs never see the fence as vertical";
  EXPECT_GE(slammable({.see_through_max_height_m = 2.0}), 1u);
  EXPECT_EQ(slammable({.see_through_max_height_m = 0.3}), 0u) << "both bars are above the limit";
}

// Ground below a canopy at 2.5 m: ground and canopy returns at one range are no wall when
// the canopy is above the see-through height.
TEST(ClassifyFan, CanopyAboveTheSeeThroughHeightIsNoWall) {
  std::vector<Eigen::Vector3f> returns = {{5.0f, 0.0f, 0.0f}, {7.0f, 0.0f, 0.0f}, {9.0f, 0.0f, 0.0f},
                                          {6.0f, 0.0f, 2.5f}, {6.05f, 0.0f, 2.8f}};
  const auto classes = Classify(returns, {.see_through_max_height_m = 2.0});
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NE(classes[i], CellClass::kSlammable) << i;
}

TEST(ClassifyFan, RampsAreHazardAboveFifteenDegrees) {
  for (const double slope_deg : {10.0, 16.0}) {
    const double t = std::tan(slope_deg * kDeg);
    const auto returns = FanOver([t](double x) { return x > 4.0 ? (x - 4.0) * t : 0.0; }, 32);
    const auto classes = Classify(returns);
    int hazard = 0, slammable = 0, on_ramp = 0;
    for (std::size_t i = 1; i < returns.size(); ++i) {
      if (returns[i - 1].x() <= 4.0f) continue;  // pairs that straddle the foot of the ramp
      ++on_ramp;
      hazard += classes[i - 1] == CellClass::kHazard;
      slammable += classes[i - 1] == CellClass::kSlammable;
    }
    ASSERT_GT(on_ramp, 3);
    EXPECT_EQ(slammable, 0) << slope_deg;
    if (slope_deg < 15.0) EXPECT_EQ(hazard, 0) << slope_deg;
    else EXPECT_GE(hazard, on_ramp - 1) << slope_deg;
  }
}

TEST(ClassifyFan, NearbyCurbIsAnObstacleAndAFarOneVanishesBetweenLasers) {
  // A 15 cm curb: at 4.5 m the 32-laser fan samples the ground every ~0.2 m, so the step
  // is far steeper than 15 deg; at 9 m the 16-laser fan's returns are ~1.5 m apart and
  // the step is a gentle slope (why the thesis fills in and fits, 7.1.3-7.1.4).
  auto obstacles = [](const std::vector<CellClass>& classes) {
    int count = 0;
    for (CellClass c : classes) count += c == CellClass::kHazard || c == CellClass::kSlammable;
    return count;
  };
  EXPECT_GE(obstacles(Classify(FanOver([](double x) { return x >= 4.5 ? 0.15 : 0.0; }, 32))), 1);
  EXPECT_EQ(obstacles(Classify(FanOver([](double x) { return x >= 9.0 ? 0.15 : 0.0; }, 16))), 0);
}

TEST(ClassifyFan, ObstacleMarkedOnTheReturnNearestTheVehicle) {
  // Two returns: ground at 3 m, then a point high on a wall at 3.05 m: the pair is
  // slammable and the mark goes to the nearer return, the one at 3 m.
  const std::vector<Eigen::Vector3f> returns{{3.0f, 0.0f, 0.0f}, {3.05f, 0.0f, 1.5f}};
  const auto classes = Classify(returns);
  EXPECT_EQ(classes[0], CellClass::kSlammable);
  EXPECT_EQ(classes[1], CellClass::kUnknown);
}

TEST(ClassifyFan, ThresholdsAreConfigurable) {
  const std::vector<Eigen::Vector3f> returns{{3.0f, 0.0f, 0.0f}, {4.0f, 0.0f, std::tan(static_cast<float>(20 * kDeg))}};
  EXPECT_EQ(Classify(returns)[0], CellClass::kHazard);
  SlopeThresholds lenient;
  lenient.hazard_slope_rad = 25 * kDeg;
  EXPECT_EQ(Classify(returns, lenient)[0], CellClass::kFree);
  SlopeThresholds strict;
  strict.slammable_slope_rad = 19 * kDeg;
  EXPECT_EQ(Classify(returns, strict)[0], CellClass::kSlammable);
}

TEST(ClassifyFan, NoiseOnFlatGroundStaysFreeWithThreePointFit) {
  std::mt19937 rng(11);
  std::normal_distribution<float> noise(0.0f, 0.03f);
  auto returns = FanOver([](double) { return 0.0; }, 32);
  for (auto& r : returns) r.z() += noise(rng) * 0.1f;  // 3 mm vertical jitter
  SlopeThresholds fit3;
  fit3.fit_points = 3;
  for (CellClass c : Classify(returns, fit3)) EXPECT_EQ(c, CellClass::kFree);
}

TEST(ClassifyFan, EmptyAndSingleReturnFans) {
  EXPECT_TRUE(Classify({}).empty());
  const std::vector<Eigen::Vector3f> one{{5.0f, 0.0f, 0.0f}};
  EXPECT_EQ(Classify(one)[0], CellClass::kFree);  // level with the dummy return
}

}  // namespace
}  // namespace flat2d::maps
