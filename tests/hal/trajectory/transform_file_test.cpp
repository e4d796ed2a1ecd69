#include "hal/trajectory/transform_file.hpp"

#include <gtest/gtest.h>

#include "tests/testing/data_path.hpp"

namespace flat2d::hal::trajectory {
namespace {

TEST(TransformFile, ReadsTheFastGicpReference) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/hdl32e_fast_gicp_pair/relative_fast_gicp.txt");
  const auto transform = ReadTransformFile(path);
  ASSERT_TRUE(transform.ok()) << transform.error().message;
  // PROVENANCE.md: about 0.50 m / 0.71 deg.
  EXPECT_NEAR(transform->translation().norm(), 0.50, 0.02);
  EXPECT_NEAR(Eigen::AngleAxisd(transform->linear()).angle() * 180.0 / M_PI, 0.71, 0.05);
}

TEST(TransformFile, RoundTripsThroughFormat) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(1.5, -2.25, 0.125);
  const auto parsed = ParseTransform(FormatTransform(t), "memory");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_LT((parsed->matrix() - t.matrix()).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(TransformFile, ReadsThreeByFourKittiLines) {
  const auto parsed = ParseTransform("1 0 0 1\n0 1 0 2\n0 0 1 3  # a KITTI pose line", "poses.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_EQ(parsed->translation(), Eigen::Vector3d(1, 2, 3));
}

TEST(TransformFile, RejectsWhatIsNotARigidTransform) {
  const auto count = ParseTransform("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0", "a.txt");
  ASSERT_FALSE(count.ok());
  EXPECT_EQ(count.error().message, "a.txt: 15 numbers, expected 16 (4x4) or 12 (3x4)");
  const auto token = ParseTransform("1 0 0 0\n0 1 x 0\n0 0 1 0\n0 0 0 1", "b.txt");
  ASSERT_FALSE(token.ok());
  EXPECT_EQ(token.error().message, "b.txt: line 2: 'x' is not a number");
  const auto scaled = ParseTransform("2 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1", "c.txt");
  ASSERT_FALSE(scaled.ok());
  EXPECT_NE(scaled.error().message.find("c.txt: the 3x3 block is not a rotation"), std::string::npos);
  const auto bottom = ParseTransform("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1", "d.txt");
  ASSERT_FALSE(bottom.ok());
  EXPECT_EQ(bottom.error().message, "d.txt: the bottom row is not 0 0 0 1");
  EXPECT_FALSE(ReadTransformFile("/nonexistent/t.txt").ok());
}

}  // namespace
}  // namespace flat2d::hal::trajectory
