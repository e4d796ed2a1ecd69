#include "maps/grid/revolution_gridder.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/config/text_proto.hpp"
#include "tests/maps/grid/wall_scene.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

namespace velodyne = hal::velodyne;
constexpr double kSpeed = 0.0005;  // m per fan: 9 m/s at 18,000 fans/s (a VLP-16 at 10 Hz)

StructureGridOptions Options() {
  StructureGridOptions options;
  const Status parsed = hal::config::LoadTextProto(
      std::string(FLAT2D_SOURCE_DIR) + "/packaging/config/grid/structure_grid.textproto", options);
  EXPECT_TRUE(parsed.ok()) << parsed.error().message;
  return options;
}

Eigen::Isometry2d Driving(std::size_t k) {
  return Eigen::Isometry2d(Eigen::Translation2d(-5.0 + kSpeed * static_cast<double>(k), 0.0));
}

// The odometry: the same drive, known by fan stamp (55.5 us per fan).
class DrivingPoses : public VehiclePoseSource {
 public:
  std::optional<Eigen::Isometry2d> PoseAt(TimeNs t) const override {
    if (t < 0) return std::nullopt;
    return Driving(static_cast<std::size_t>(t / 55'500));
  }
};

// Slammable cells whose centre is within 1.5 cells of where the wall is in the grid frame.
std::pair<int, int> WallCells(const PublishedGrid& published) {
  const double wall_in_grid = kWallX - published.local_T_grid.translation().x();
  int on = 0, off = 0;
  const GridGeometry& g = published.grid->geometry();
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (published.grid->at({col, row}) != CellClass::kSlammable) continue;
      const Eigen::Vector2d c = g.CellCenter({col, row});
      (std::abs(c.x() - wall_in_grid) <= 1.5 * g.resolution_m ? on : off) += 1;
    }
  }
  return {on, off};
}

TEST(RevolutionGridder, PublishesOneMotionCompensatedGridPerTurn) {
  const StructureGridOptions options = Options();
  // Three turns of fans starting mid-turn: a partial first turn, two complete, a partial last.
  const auto fans = WallSceneFans(options, 3 * kWallSceneFansPerTurn, Driving, 900);
  const DrivingPoses poses;
  auto gridder = RevolutionGridder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options, &poses);
  ASSERT_TRUE(gridder.ok()) << gridder.error().message;

  std::vector<PublishedGrid> published;
  std::vector<std::pair<int, int>> wall;
  for (std::size_t k = 0; k < fans.size(); k += 24) {  // a VLP-16 packet holds 24 fans
    const std::size_t end = std::min(fans.size(), k + 24);
    if (const PublishedGrid* grid = gridder->Add(std::span(fans).subspan(k, end - k))) {
      published.push_back(*grid);
      wall.push_back(WallCells(*grid));  // read now: valid until the next completion
    }
  }
  const PublishedGrid* last = gridder->Flush();
  ASSERT_NE(last, nullptr);
  ASSERT_EQ(published.size(), 3u);
  EXPECT_FALSE(published[0].complete);
  EXPECT_EQ(published[0].fans, 900);
  for (std::size_t i = 1; i < 3; ++i) {
    const PublishedGrid& grid = published[i];
    EXPECT_TRUE(grid.complete);
    EXPECT_EQ(grid.sequence, i);
    EXPECT_EQ(grid.fans, static_cast<int>(kWallSceneFansPerTurn));
    EXPECT_EQ(grid.fans_without_pose, 0);
    // The reference pose is the vehicle's at the turn's first fan.
    EXPECT_NEAR(grid.local_T_grid.translation().x(),
                Driving(static_cast<std::size_t>(grid.start_ns / 55'500)).translation().x(), 1e-9);
    EXPECT_GT(wall[i].first, 100) << i;
    EXPECT_EQ(wall[i].second, 0) << i;
  }
  EXPECT_FALSE(last->complete);
  EXPECT_EQ(last->fans, 900);
}

TEST(RevolutionGridder, WithoutPosesTheSensorStandsStill) {
  const StructureGridOptions options = Options();
  auto still = [](std::size_t) { return Eigen::Isometry2d::Identity(); };
  const auto fans = WallSceneFans(options, 2 * kWallSceneFansPerTurn + 10, still);
  auto gridder = RevolutionGridder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options, nullptr);
  ASSERT_TRUE(gridder.ok());
  const PublishedGrid* first = gridder->Add(std::span(fans).first(kWallSceneFansPerTurn + 5));
  ASSERT_NE(first, nullptr);
  EXPECT_TRUE(first->complete == false);  // the stream began at the cut, not at a wrap
  EXPECT_TRUE(first->local_T_grid.isApprox(Eigen::Isometry2d::Identity()));
  EXPECT_GT(WallCells(*first).first, 100);
}

TEST(RevolutionGridder, SteadyStateAllocatesNothing) {
  const StructureGridOptions options = Options();
  const auto fans = WallSceneFans(options, 3 * kWallSceneFansPerTurn, Driving);
  const DrivingPoses poses;
  auto gridder = RevolutionGridder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options, &poses);
  ASSERT_TRUE(gridder.ok());
  const auto before = testing::AllocationCount();
  int published = 0;
  for (std::size_t k = 0; k < fans.size(); k += 24) published += gridder->Add(std::span(fans).subspan(k, 24)) != nullptr;
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_EQ(published, 2);
}

}  // namespace
}  // namespace flat2d::maps
