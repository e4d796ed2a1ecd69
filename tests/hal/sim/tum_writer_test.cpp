// TUM lines: exact times from integer nanoseconds, 9 decimals, one quaternion sign, and
// refusals of what the format cannot hold.
#include "hal/sim/tum_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/hal/sim/simulation_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

Eigen::Isometry3d Pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(x, y, z));
  pose.rotate(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return pose;
}

TEST(TumWriter, TimeComesFromIntegerNanosecondsExactly) {
  // 1767225600.000000001 is not representable as a double; the line must still say it.
  EXPECT_EQ(FormatTumLine(1'767'225'600'000'000'001, Pose(1.5, -2.25, 0.125, 0.0)),
            "1767225600.000000001 1.500000000 -2.250000000 0.125000000 0.000000000 0.000000000 "
            "0.000000000 1.000000000");
  EXPECT_EQ(FormatTumLine(0, Eigen::Isometry3d::Identity()).substr(0, 12), "0.000000000 ");
}

TEST(TumWriter, QuaternionIsTheRotationWithNonNegativeW) {
  // A yaw of 3 rad and of 3 - 2 pi are one rotation; Eigen may give either sign.
  const std::string a = FormatTumLine(kNsPerSecond, Pose(0, 0, 0, 3.0));
  const std::string b = FormatTumLine(kNsPerSecond, Pose(0, 0, 0, 3.0 - 2.0 * std::numbers::pi));
  EXPECT_EQ(a, b);
  double t, x, y, z, qx, qy, qz, qw;
  ASSERT_EQ(std::sscanf(a.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf", &t, &x, &y, &z, &qx, &qy, &qz, &qw), 8);
  EXPECT_GE(qw, 0.0);
  EXPECT_NEAR(qz, std::sin(1.5), 1e-9);
  EXPECT_NEAR(qw, std::cos(1.5), 1e-9);
}

TEST(TumWriter, WritesLinesAndRefusesBadPoses) {
  testing::ScratchDir dir("tum");
  std::filesystem::create_directories(dir.path());
  auto writer = TumWriter::Open(dir.path() / "t.tum");
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  EXPECT_TRUE(writer->Write(1'000'000'000, Pose(1, 2, 3, 0.5)).ok());
  EXPECT_TRUE(writer->Write(1'005'000'000, Pose(1, 2, 3, 0.5)).ok());
  EXPECT_FALSE(writer->Write(-1, Pose(0, 0, 0, 0)).ok());
  EXPECT_FALSE(writer->Write(2'000'000'000, Pose(std::nan(""), 0, 0, 0)).ok());
  EXPECT_EQ(writer->poses_written(), 2u);
  ASSERT_TRUE(writer->Close().ok());
  EXPECT_EQ(testing::ReadBytes(dir.path() / "t.tum"),
            FormatTumLine(1'000'000'000, Pose(1, 2, 3, 0.5)) + "\n" +
                FormatTumLine(1'005'000'000, Pose(1, 2, 3, 0.5)) + "\n");
  EXPECT_FALSE(TumWriter::Open(dir.path() / "missing" / "t.tum").ok());
}

}  // namespace
}  // namespace flat2d::hal::sim
