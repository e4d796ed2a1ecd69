#include "localization/loops/closure_validation.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "maps/range3d/neighbour_statistics.hpp"
#include "maps/range3d/range_frame.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::localization::loops {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d Pose(double x, double y, double z, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  pose.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

// A "local map": the scene (the office room unless said) seen by an HDL-32E at world_T_map,
// in the map's frame, with statistics over R = 0.3 m as the store reads maps back.
maps::range3d::SurfelCloud MapAt(const Eigen::Isometry3d& world_T_map,
                                 const testing::BoxScene& scene = testing::OfficeRoom()) {
  const maps::range3d::RangeProjection lidar = maps::range3d::LidarProjection(maps::range3d::SensorModel::kHdl32e, 1080);
  maps::range3d::SurfelCloud cloud;
  const std::vector<Eigen::Vector3f> points = testing::RenderLidar(scene, lidar, world_T_map.cast<float>());
  cloud.Resize(points.size());
  cloud.points = points;
  maps::range3d::SurfaceStatisticsOptions statistics;
  statistics.radius_m = 0.3F;
  maps::range3d::ComputeNeighbourStatistics(statistics, Eigen::Vector3f::Zero(), cloud);
  return cloud;
}

struct Offsets {
  double translation_m;
  double rotation_deg;
};

Offsets Between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d error = a.inverse() * b;
  return {error.translation().norm(), Eigen::AngleAxisd(error.linear()).angle() / kDeg};
}

class ClosureValidationTest : public ::testing::Test {
 protected:
  const Eigen::Isometry3d world_T_reference = Pose(2.0, 2.0, 1.2, 0.0);
  const Eigen::Isometry3d world_T_current = Pose(3.0, 2.6, 1.2, 25.0);
  const Eigen::Isometry3d truth = world_T_reference.inverse() * world_T_current;
  const maps::range3d::SurfelCloud reference = MapAt(world_T_reference);
  const maps::range3d::SurfelCloud current = MapAt(world_T_current);
};

// A path alignment's guess, up to a lane off (0.8 m, 5 deg): beyond Eq. 5.6's 0.5 m, hence
// the rounds of shrinking pair distance.
TEST_F(ClosureValidationTest, AcceptsAGuessALaneOffAndRegistersTheMapsOnEachOther) {
  const Eigen::Isometry3d guess = truth * Pose(0.6, -0.5, 0.1, 5.0);
  const ClosureValidation v = ValidateClosure(reference, current, guess, ClosureValidationOptions{});
  ASSERT_TRUE(v.accepted) << v.reason;
  const Offsets error = Between(truth, v.result.target_T_source);
  EXPECT_LT(error.translation_m, 0.02);
  EXPECT_LT(error.rotation_deg, 0.2);
  EXPECT_GT(v.inlier_share, 0.5);
}

// Eq. 5.6 alone (one round at 0.5 m) does not reach that guess; the rounds do.
TEST_F(ClosureValidationTest, OneRoundAtHalfAMetreDoesNotReachTheSameGuess) {
  const Eigen::Isometry3d guess = truth * Pose(0.6, -0.5, 0.1, 5.0);
  ClosureValidationOptions one_round;
  for (float& d : one_round.round_distances_m) d = 0.5F;
  one_round.nicp.iterations = 4;
  const ClosureValidation v = ValidateClosure(reference, current, guess, one_round);
  const Offsets error = Between(truth, v.result.target_T_source);
  EXPECT_TRUE(!v.accepted || error.translation_m > 0.02) << error.translation_m;
}

// A false candidate: the current map claimed to lie on the reference map (identity), half a
// room and 25 deg from the truth. Whatever NICP finds from there, it is not accepted as the
// closure proposed.
TEST_F(ClosureValidationTest, RejectsACandidateThatClaimsTheWrongPlace) {
  const ClosureValidation v = ValidateClosure(reference, current, Pose(0, 0, 0, 90.0), ClosureValidationOptions{});
  EXPECT_FALSE(v.accepted);
  EXPECT_FALSE(v.reason.empty());
}

TEST_F(ClosureValidationTest, RejectsMapsThatDoNotOverlap) {
  maps::range3d::SurfelCloud far = current;
  for (auto& p : far.points) p += Eigen::Vector3f(40.0F, 0.0F, 0.0F);
  const ClosureValidation v = ValidateClosure(reference, far, truth, ClosureValidationOptions{});
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("registration failed"), std::string::npos) << v.reason;
}

// A corridor 3 m wide and 1 km long, nothing along it: two maps fit anywhere along it.
testing::BoxScene Corridor() { return {{{-500.0F, -1.5F, 0.0F}, {500.0F, 1.5F, 3.0F}}, {}}; }

// The uniqueness test (step 3) on a candidate that is right but has nothing to hold it along
// the corridor: the fit from 3 m further along is as good, so it is refused; the office room
// holds its fit in every direction and passes.
TEST_F(ClosureValidationTest, TheUniquenessTestRefusesAFitThatSlidesAlongACorridor) {
  ClosureValidationOptions unique;
  unique.ambiguity_shift_m = 3.0;
  const Eigen::Isometry3d a = Pose(0.0, 0.0, 1.2, 0.0), b = Pose(1.0, 0.3, 1.2, 3.0);
  const Eigen::Isometry3d corridor_truth = a.inverse() * b;
  const maps::range3d::SurfelCloud corridor_a = MapAt(a, Corridor()), corridor_b = MapAt(b, Corridor());
  const ClosureValidation plain = ValidateClosure(corridor_a, corridor_b, corridor_truth, ClosureValidationOptions{});
  ASSERT_TRUE(plain.accepted) << plain.reason;  // the fit itself passes steps 1-2
  const ClosureValidation v = ValidateClosure(corridor_a, corridor_b, corridor_truth, unique);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("ambiguous"), std::string::npos) << v.reason;

  const ClosureValidation room = ValidateClosure(reference, current, truth * Pose(0.3, -0.2, 0.0, 2.0), unique);
  ASSERT_TRUE(room.accepted) << room.reason;
  EXPECT_LT(Between(truth, room.result.target_T_source).translation_m, 0.02);
}

// A street 8 m wide between walls, with a pillar on each side every 10 m: every stretch of
// it looks like the next.
testing::BoxScene PeriodicStreet() {
  testing::BoxScene street{{{-500.0F, -4.0F, 0.0F}, {500.0F, 4.0F, 4.0F}}, {}};
  for (int k = -50; k <= 50; ++k) {
    const float x = 10.0F * static_cast<float>(k);
    street.furniture.push_back({{x - 0.3F, 3.0F, 0.0F}, {x + 0.3F, 3.6F, 4.0F}});
    street.furniture.push_back({{x - 0.3F, -3.6F, 0.0F}, {x + 0.3F, -3.0F, 4.0F}});
  }
  return street;
}

// The alias test: on the periodic street the current map fits the reference's neighbours,
// 10 m on, as well as the reference itself, and the closure is refused; in the office room
// the current map put on a neighbour as on the reference comes back to the same place.
TEST_F(ClosureValidationTest, TheAliasTestRefusesAPlaceWhoseLookRepeats) {
  const Eigen::Isometry3d a = Pose(2.0, 0.0, 1.2, 0.0), b = Pose(3.0, 0.3, 1.2, 3.0);
  const maps::range3d::SurfelCloud street_a = MapAt(a, PeriodicStreet()), street_b = MapAt(b, PeriodicStreet());
  const ClosureValidation fit = ValidateClosure(street_a, street_b, a.inverse() * b, ClosureValidationOptions{});
  ASSERT_TRUE(fit.accepted) << fit.reason;
  EXPECT_LT(Between(a.inverse() * b, fit.result.target_T_source).translation_m, 0.05);
  const Eigen::Isometry3d n = Pose(12.0, 0.0, 1.2, 0.0);
  const maps::range3d::SurfelCloud street_n = MapAt(n, PeriodicStreet());
  const AliasNeighbour street_neighbour{7, &street_n, a.inverse() * n};
  const std::string alias = FindAlias(street_b, fit, street_neighbour, ClosureValidationOptions{});
  EXPECT_NE(alias.find("aliased: map 7"), std::string::npos) << alias;

  const ClosureValidation room = ValidateClosure(reference, current, truth, ClosureValidationOptions{});
  ASSERT_TRUE(room.accepted) << room.reason;
  const Eigen::Isometry3d m = Pose(3.5, 1.5, 1.2, -20.0);
  const maps::range3d::SurfelCloud room_m = MapAt(m);
  const AliasNeighbour room_neighbour{3, &room_m, world_T_reference.inverse() * m};
  EXPECT_EQ(FindAlias(current, room, room_neighbour, ClosureValidationOptions{}), "");
}

}  // namespace
}  // namespace flat2d::localization::loops
