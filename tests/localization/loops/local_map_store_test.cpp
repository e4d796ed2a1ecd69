#include "localization/loops/local_map_store.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "localization/loops/closure_edits.hpp"

namespace flat2d::localization::loops {
namespace {

std::filesystem::path TestDirectory(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("flat2d_local_map_store_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

// A wall (x = 3, facing the origin) sampled every 2 cm, in the world frame.
maps::range3d::SurfelCloud Wall() {
  maps::range3d::SurfelCloud cloud;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) {
      cloud.points.emplace_back(3.0F, -1.0F + 0.02F * static_cast<float>(i), 0.02F * static_cast<float>(j));
    }
  }
  cloud.normals.assign(cloud.points.size(), Eigen::Vector3f(-1.0F, 0.0F, 0.0F));
  cloud.normals[0].setZero();  // undefined: not written
  return cloud;
}

TEST(LocalMapStore, WritesOnePointPerVoxelInTheMapFrameAndReadsThemBackWithStatistics) {
  const LocalMapStore store(TestDirectory("round_trip"), LocalMapStoreOptions{});
  ASSERT_TRUE(store.Create().ok());
  Eigen::Isometry3d world_T_map = Eigen::Isometry3d::Identity();
  world_T_map.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  ASSERT_TRUE(store.WritePoints(7, Wall(), world_T_map).ok());
  EXPECT_EQ(store.PointsPath(7).filename(), "map_0007.ply");

  auto stored = store.ReadStored(7);
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  // 2 m x 2 m at 0.1 m voxels: 20 x 20 (the wall's plane x = 2 in the map frame).
  EXPECT_NEAR(static_cast<double>(stored->points.size()), 400.0, 21.0);
  for (const auto& p : stored->points) EXPECT_FLOAT_EQ(p.x(), 2.0F);

  auto read = store.ReadPoints(7);
  ASSERT_TRUE(read.ok()) << read.error().message;
  int with_normal = 0;
  for (std::size_t i = 0; i < read->size(); ++i) {
    if (!read->has_normal(i)) continue;
    ++with_normal;
    EXPECT_NEAR(read->normals[i].x(), -1.0F, 1e-3F);  // the stored side, fitted again
  }
  EXPECT_GT(with_normal, 300);
}

TEST(LocalMapStore, AMissingMapIsAnErrorNamingTheFile) {
  const LocalMapStore store(TestDirectory("missing"), LocalMapStoreOptions{});
  ASSERT_TRUE(store.Create().ok());
  auto read = store.ReadPoints(3);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().message.find("map_0003.ply"), std::string::npos) << read.error().message;
}

TEST(ClosureEdits, ParsesAdditionsAndRemovalsWithComments) {
  auto edits = ParseClosureEdits("# refiner\nadd 3 40 1.5 -2 0 0 0 0.7071068 0.7071068  # a turn\n\nremove 5 61\n", "edits");
  ASSERT_TRUE(edits.ok()) << edits.error().message;
  ASSERT_EQ(edits->additions.size(), 1U);
  EXPECT_EQ(edits->additions[0].reference, 3);
  EXPECT_EQ(edits->additions[0].current, 40);
  EXPECT_NEAR(edits->additions[0].reference_T_current.translation().x(), 1.5, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(edits->additions[0].reference_T_current.linear()).angle(), M_PI / 2.0, 1e-6);
  ASSERT_EQ(edits->removals.size(), 1U);
  EXPECT_EQ(edits->removals[0], std::make_pair(5, 61));
}

TEST(ClosureEdits, ErrorsNameTheLineAndTheProblem) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"remove 1 2\nmerge 1 2\n", "edits: line 2: unknown edit 'merge'"},
      {"remove 1\n", "line 1: remove takes 2 fields, found 1"},
      {"add 1 2 0 0 0 0 0 0\n", "line 1: add takes 9 fields, found 8"},
      {"remove -1 2\n", "line 1: map indices are integers >= 0"},
      {"add 1 2 0 0 x 0 0 0 1\n", "line 1: field 6 is not a number"},
      {"\n\nadd 1 2 0 0 0 0 0 0 2\n", "line 3: the quaternion is not unit length"},
  };
  for (const Case& c : cases) {
    auto edits = ParseClosureEdits(c.text, "edits");
    ASSERT_FALSE(edits.ok()) << c.text;
    EXPECT_NE(edits.error().message.find(c.expected), std::string::npos) << edits.error().message;
  }
}

}  // namespace
}  // namespace flat2d::localization::loops
