#include "maps/grid/interpolated_poses.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(InterpolatedPoses, InterpolatesPositionAndTheShorterArcOfHeading) {
  const InterpolatedPoses poses({{1000, {0.0, 0.0}, kPi - 0.1}, {2000, {2.0, 4.0}, -kPi + 0.1}});
  const auto mid = poses.PoseAt(1500);
  ASSERT_TRUE(mid);
  EXPECT_TRUE(mid->translation().isApprox(Eigen::Vector2d(1.0, 2.0)));
  // Across +-pi: halfway between pi - 0.1 and -pi + 0.1 is pi, not 0.
  EXPECT_NEAR(std::abs(Eigen::Rotation2Dd(mid->linear()).smallestAngle()), kPi, 1e-12);
  EXPECT_TRUE(poses.PoseAt(1000)->translation().isZero());
  EXPECT_TRUE(poses.PoseAt(2000)->translation().isApprox(Eigen::Vector2d(2.0, 4.0)));
  EXPECT_FALSE(poses.PoseAt(999));
  EXPECT_FALSE(poses.PoseAt(2001));
  EXPECT_FALSE(InterpolatedPoses({}).PoseAt(0));
}

TEST(InterpolatedPoses, FlattenTakesYawFromTheBodyXAxis) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();  // yaw 0.7 and pitched up a ramp
  pose.translation() = Eigen::Vector3d(3.0, -1.0, 2.0);
  const StampedPose2d flat = Flatten(42, pose);
  EXPECT_EQ(flat.time_ns, 42);
  EXPECT_NEAR(flat.yaw, 0.7, 1e-12);
  EXPECT_EQ(flat.position, Eigen::Vector2d(3.0, -1.0));
}

}  // namespace
}  // namespace flat2d::maps
