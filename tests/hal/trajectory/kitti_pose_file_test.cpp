#include "hal/trajectory/kitti_pose_file.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/testing/data_path.hpp"

namespace flat2d::hal::trajectory {
namespace {

TEST(KittiPoseFile, ReadsSequence00) {
  FLAT2D_REQUIRE_DATA(path, "lidar3d/kitti_odometry_00_frames_000000-000015/poses_00_full_4541.txt");
  const auto poses = ReadKittiPoses(path);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  ASSERT_EQ(poses->size(), 4541u);
  EXPECT_LT(poses->front().translation().norm(), 1e-9);
  // Line 2 of the file: the second frame 0.859 m ahead along the camera's z.
  EXPECT_NEAR((*poses)[1].translation().z(), 0.8586941, 1e-7);
  double length = 0.0;
  for (std::size_t i = 1; i < poses->size(); ++i) {
    length += ((*poses)[i].translation() - (*poses)[i - 1].translation()).norm();
  }
  // Sequence 00 is about 3.7 km (KITTI odometry benchmark).
  EXPECT_NEAR(length, 3724.0, 50.0);
}

TEST(KittiPoseFile, TheVehicleFrameLooksForwardAlongX) {
  Eigen::Isometry3d world_T_cam = Eigen::Isometry3d::Identity();
  world_T_cam.translation() = Eigen::Vector3d(0.5, -0.2, 10.0);  // 10 m forward, 0.2 m up, 0.5 m right
  world_T_cam.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();  // about the camera's down axis
  const Eigen::Isometry3d vehicle = VehicleFromKittiCamera(world_T_cam);
  EXPECT_TRUE(vehicle.translation().isApprox(Eigen::Vector3d(10.0, -0.5, 0.2), 1e-12)) << vehicle.translation().transpose();
  // A turn about the camera's y (down) is a turn about the vehicle's -z: to the right.
  const Eigen::AngleAxisd turn(vehicle.linear());
  EXPECT_NEAR(turn.angle(), 0.3, 1e-12);
  EXPECT_NEAR(turn.axis().z(), -1.0, 1e-12);
}

TEST(KittiPoseFile, ABadLineIsAnErrorNamingIt) {
  const auto short_line = ParseKittiPoses("1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n", "poses.txt");
  ASSERT_FALSE(short_line.ok());
  EXPECT_NE(short_line.error().message.find("poses.txt: line 2"), std::string::npos) << short_line.error().message;
  const auto not_rotation = ParseKittiPoses("2 0 0 0 0 1 0 0 0 0 1 0\n", "poses.txt");
  ASSERT_FALSE(not_rotation.ok());
  EXPECT_NE(not_rotation.error().message.find("line 1"), std::string::npos);
  const auto empty = ParseKittiPoses("\n\n", "poses.txt");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().message, "poses.txt: no poses");
  EXPECT_FALSE(ReadKittiPoses("/nonexistent/poses.txt").ok());
}

TEST(KittiCalibration, TrIsTheVelodyneInTheCameraFrame) {
  const auto tr = ParseKittiCalibration("P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: 0 -1 0 -0.01 0 0 -1 -0.05 1 0 0 -0.29\n", "calib.txt");
  ASSERT_TRUE(tr.ok()) << tr.error().message;
  // The Velodyne's forward axis (x) is the camera's z, its up (z) the camera's -y.
  EXPECT_TRUE((tr->linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((tr->linear() * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_EQ(ParseKittiCalibration("P0: 1 0 0 0 0 1 0 0 0 0 1 0\n", "calib.txt").error().message,
            "calib.txt: no Tr: line (cam0_T_velo)");
  const auto bad = ParseKittiCalibration("P0: 1\nTr: 2 0 0 0 0 1 0 0 0 0 1 0\n", "calib.txt");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("calib.txt: line 2"), std::string::npos) << bad.error().message;
}

TEST(KittiCalibration, VelodynePosesOfSequence00DriveForwardOnTheGround) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/kitti_odometry_00_frames_000000-000015");
  const auto poses = ReadKittiPoses(folder / "poses.txt");
  const auto tr = ReadKittiCalibration(folder / "calib.txt");
  ASSERT_TRUE(poses.ok() && tr.ok());
  const std::vector<Eigen::Isometry3d> velo = VelodyneFromKittiCamera(*poses, *tr);
  ASSERT_EQ(velo.size(), 16u);
  EXPECT_TRUE(velo.front().isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  // poses.txt's last line: the camera 12.87 m forward (z), 0.70 m left (-x), 0.42 m up (-y);
  // the Velodyne, 0.27 m behind it, sees the same within the lever arm's turn.
  const Eigen::Vector3d end = velo.back().translation();
  EXPECT_NEAR(end.x(), 12.87, 0.05);
  EXPECT_NEAR(end.y(), 0.70, 0.05);
  EXPECT_NEAR(end.z(), 0.42, 0.12);
}

}  // namespace
}  // namespace flat2d::hal::trajectory
