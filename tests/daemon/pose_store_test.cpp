// The persisted pose (daemon/service/pose_store.hpp): written atomically, read back exactly,
// damaged files refused with the path in the error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "daemon/service/pose_store.hpp"

namespace flat2d::daemon {
namespace {

class PoseStore : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("flat2d_pose_store_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(PoseStore, RoundTripsAndReplacesAtomically) {
  const auto path = dir_ / "last_pose.textproto";
  PersistedPose pose;
  pose.set_time_ns(1767225605921000004);
  pose.set_x(-8.179123456789);
  pose.set_y(10.029);
  pose.set_theta(-0.0012);
  pose.set_map("/var/lib/flat2d/map.f2m");
  ASSERT_TRUE(SavePersistedPose(path, pose).ok());
  pose.set_x(1.25);
  ASSERT_TRUE(SavePersistedPose(path, pose).ok());
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  auto loaded = LoadPersistedPose(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->time_ns(), 1767225605921000004);
  EXPECT_DOUBLE_EQ(loaded->x(), 1.25);
  EXPECT_DOUBLE_EQ(loaded->theta(), -0.0012);
  EXPECT_EQ(loaded->map(), "/var/lib/flat2d/map.f2m");
}

TEST_F(PoseStore, RefusesDamagedAndMissingFiles) {
  const auto path = dir_ / "damaged.textproto";
  std::ofstream(path) << "x: 1.0\ny: \"north\"\n";
  auto damaged = LoadPersistedPose(path);
  ASSERT_FALSE(damaged.ok());
  EXPECT_NE(damaged.error().message.find(path.string()), std::string::npos) << damaged.error().message;
  std::ofstream(path) << "x: nan\n";
  EXPECT_FALSE(LoadPersistedPose(path).ok());
  EXPECT_FALSE(LoadPersistedPose(dir_ / "absent.textproto").ok());
  EXPECT_FALSE(SavePersistedPose(dir_ / "no/such/folder/pose.textproto", PersistedPose()).ok());
}

}  // namespace
}  // namespace flat2d::daemon
