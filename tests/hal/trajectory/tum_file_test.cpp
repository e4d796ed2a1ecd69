#include "hal/trajectory/tum_file.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace flat2d::hal::trajectory {
namespace {

TEST(TumFile, ParsesPosesWithExactNanosecondTimes) {
  const double s = std::sin(std::numbers::pi / 8.0), c = std::cos(std::numbers::pi / 8.0);  // yaw 45 deg
  const std::string text = "# t x y z qx qy qz qw\n"
                           "1767225600.000000001 1.5 -2 0.25 0 0 0 1\n"
                           "\n"
                           "1767225600.1 10 20 0 0 0 " + std::to_string(s) + " " + std::to_string(c) + "  # comment\n";
  const auto poses = ParseTum(text, "truth.tum");
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  ASSERT_EQ(poses->size(), 2u);
  EXPECT_EQ((*poses)[0].time_ns, 1'767'225'600'000'000'001);
  EXPECT_EQ((*poses)[1].time_ns, 1'767'225'600'100'000'000);
  EXPECT_EQ((*poses)[0].world_T_body.translation(), Eigen::Vector3d(1.5, -2.0, 0.25));
  const Eigen::Vector3d x_axis = (*poses)[1].world_T_body.linear().col(0);
  EXPECT_NEAR(std::atan2(x_axis.y(), x_axis.x()), std::numbers::pi / 4.0, 1e-5);  // 6 decimals in the text
}

TEST(TumFile, MalformedLinesAreErrorsWithTheLineNumber) {
  EXPECT_EQ(ParseTum("1 0 0 0 0 0 0\n", "a.tum").error().message, "a.tum:1: expected 8 fields: t x y z qx qy qz qw");
  EXPECT_EQ(ParseTum("1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", "a.tum").error().message,
            "a.tum:2: time does not increase");
  EXPECT_EQ(ParseTum("1 0 0 0 0 0 0 2\n", "a.tum").error().message, "a.tum:1: quaternion is not unit length");
  EXPECT_EQ(ParseTum("x 0 0 0 0 0 0 1\n", "a.tum").error().message, "a.tum:1: bad time");
  EXPECT_EQ(ParseTum("1.0000000001 0 0 0 0 0 0 1\n", "a.tum").error().message, "a.tum:1: bad time");
  EXPECT_EQ(ParseTum("1 nan 0 0 0 0 0 1\n", "a.tum").error().message, "a.tum:1: bad number 'nan'");
  EXPECT_EQ(ParseTum("1 0 0 0 0 0 0 1 9\n", "a.tum").error().message, "a.tum:1: more than 8 fields");
  EXPECT_FALSE(ReadTum("/nonexistent/truth.tum").ok());
}

TEST(TumFile, WrittenPosesReadBackExactly) {
  std::vector<StampedPose> poses(2);
  poses[0].time_ns = 1305031229528784000;
  poses[0].world_T_body.translation() = Eigen::Vector3d(1.25, -0.5, 2.0);
  poses[1].time_ns = 1305031229564442123;
  poses[1].world_T_body.linear() = Eigen::AngleAxisd(2.5, Eigen::Vector3d(0.3, -1, 0.2).normalized()).toRotationMatrix();
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "flat2d_tum_write_test.tum";
  ASSERT_TRUE(WriteTum(poses, path).ok());
  const auto read = ReadTum(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_EQ(read->size(), 2U);
  EXPECT_EQ((*read)[1].time_ns, poses[1].time_ns);
  EXPECT_LT(((*read)[0].world_T_body.translation() - poses[0].world_T_body.translation()).norm(), 1e-7);
  EXPECT_LT(((*read)[1].world_T_body.linear() - poses[1].world_T_body.linear()).cwiseAbs().maxCoeff(), 1e-8);
  std::filesystem::remove(path);
  EXPECT_FALSE(WriteTum(poses, "/nonexistent/dir/t.tum").ok());
}

}  // namespace
}  // namespace flat2d::hal::trajectory
