#include "maps/grid/structure_grid_builder.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "hal/config/text_proto.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "tests/maps/grid/wall_scene.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

namespace velodyne = hal::velodyne;

StructureGridOptions Options(StructureGridOptions::Method method, bool fill_in = true) {
  StructureGridOptions options;
  const Status parsed = hal::config::LoadTextProto(
      std::string(FLAT2D_SOURCE_DIR) + "/packaging/config/grid/structure_grid.textproto", options);
  EXPECT_TRUE(parsed.ok()) << parsed.error().message;
  options.set_method(method);
  options.mutable_fill_in()->set_enabled(fill_in);
  return options;
}

const ClassGrid& Build(StructureGridBuilder& builder, const std::vector<velodyne::Fan>& fans,
                       const std::function<Eigen::Isometry2d(std::size_t)>& grid_T_vehicle) {
  builder.Begin();
  for (std::size_t k = 0; k < fans.size(); ++k) builder.AddFan(fans[k], grid_T_vehicle(k));
  return builder.Finish();
}

struct WallStats {
  int on_wall = 0;        // slammable cells within one cell of the wall's face
  int off_wall = 0;       // slammable cells farther away
  int wall_rows = 0;      // rows |y| < 4 m with a slammable cell at the wall
  double free_ground = 0; // fraction of free cells in the ground patch 3 < x < 8, |y| < 2
};

WallStats Measure(const ClassGrid& grid) {
  WallStats stats;
  const GridGeometry& g = grid.geometry();
  int ground = 0, free = 0;
  for (int row = 0; row < g.height; ++row) {
    bool row_has_wall = false;
    for (int col = 0; col < g.width; ++col) {
      const Eigen::Vector2d c = g.CellCenter({col, row});
      const CellClass cell = grid.at({col, row});
      if (cell == CellClass::kSlammable) {
        // The face is at x = 10: cells whose centre lies within 1.5 cells of it.
        if (std::abs(c.x() - kWallX) <= 1.5 * g.resolution_m && std::abs(c.y()) < 8.0) {
          ++stats.on_wall;
          row_has_wall = true;
        } else {
          ++stats.off_wall;
        }
      }
      if (c.x() > 3.0 && c.x() < 8.0 && std::abs(c.y()) < 2.0) ++ground, free += cell == CellClass::kFree;
    }
    if (row_has_wall && std::abs(g.CellCenter({0, row}).y()) < 4.0) ++stats.wall_rows;
  }
  stats.free_ground = ground == 0 ? 0.0 : static_cast<double>(free) / ground;
  return stats;
}

Eigen::Isometry2d Static(std::size_t) { return Eigen::Isometry2d::Identity(); }

TEST(StructureGridBuilder, SlopeMethodFindsTheWallAndTheFreeGround) {
  for (const bool fill_in : {false, true}) {
    const StructureGridOptions options = Options(StructureGridOptions::METHOD_SLOPE, fill_in);
    auto builder = StructureGridBuilder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options);
    ASSERT_TRUE(builder.ok()) << builder.error().message;
    const WallStats stats = Measure(Build(*builder, WallSceneRevolution(options, Static), Static));
    const int rows = static_cast<int>(8.0 / options.resolution_m());  // |y| < 4 m
    EXPECT_EQ(stats.off_wall, 0) << "fill_in " << fill_in;
    EXPECT_GE(stats.free_ground, 0.95) << "fill_in " << fill_in;
    // With fill-in the wall is continuous; without, fans 3.5 cm apart at 10 m still hit most rows.
    EXPECT_GE(stats.wall_rows, fill_in ? rows - 2 : rows * 8 / 10) << "fill_in " << fill_in;
  }
}

TEST(StructureGridBuilder, PopcountMethodsFindTheWall) {
  for (const auto method : {StructureGridOptions::METHOD_CARTESIAN_POPCOUNT,
                            StructureGridOptions::METHOD_POLAR_POPCOUNT}) {
    const StructureGridOptions options = Options(method);
    auto builder = StructureGridBuilder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options);
    ASSERT_TRUE(builder.ok()) << builder.error().message;
    const ClassGrid& grid = Build(*builder, WallSceneRevolution(options, Static), Static);
    const WallStats stats = Measure(grid);
    EXPECT_GT(stats.wall_rows, 8.0 / options.resolution_m() / 2) << method;
    // Polar bins are 0.2 deg wide (3.5 cm at 10 m) but centred on the bin, so a wall cell may
    // land one cell off; only Cartesian must be exact.
    if (method == StructureGridOptions::METHOD_CARTESIAN_POPCOUNT) {
      EXPECT_EQ(stats.off_wall, 0);
    }
    EXPECT_GE(stats.free_ground, 0.5) << method;
  }
}

// The vehicle drives 1 m forward during the revolution. With each fan placed at its own pose
// the wall stays within a cell of x = 10; placed at the revolution's start pose, it smears.
TEST(StructureGridBuilder, MotionCompensationKeepsTheWallSharp) {
  const StructureGridOptions options = Options(StructureGridOptions::METHOD_SLOPE);
  auto moving = [](std::size_t k) {
    return Eigen::Isometry2d(Eigen::Translation2d(static_cast<double>(k) / 1800.0, 0.0));
  };
  const auto fans = WallSceneRevolution(options, moving);
  auto builder = StructureGridBuilder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options);
  ASSERT_TRUE(builder.ok());
  const WallStats compensated = Measure(Build(*builder, fans, moving));
  EXPECT_EQ(compensated.off_wall, 0);
  const WallStats uncompensated = Measure(Build(*builder, fans, Static));
  EXPECT_GT(uncompensated.off_wall, 50);
}

TEST(StructureGridBuilder, BuildingARevolutionAllocatesNothing) {
  for (const auto method : {StructureGridOptions::METHOD_SLOPE, StructureGridOptions::METHOD_CARTESIAN_POPCOUNT,
                            StructureGridOptions::METHOD_POLAR_POPCOUNT}) {
    const StructureGridOptions options = Options(method);
    const auto fans = WallSceneRevolution(options, Static);
    auto builder = StructureGridBuilder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options);
    ASSERT_TRUE(builder.ok());
    const auto before = testing::AllocationCount();
    builder->Begin();
    for (const velodyne::Fan& fan : fans) builder->AddFan(fan, Eigen::Isometry2d::Identity());
    builder->Finish();
    EXPECT_EQ(testing::AllocationCount(), before) << method;
  }
}

TEST(StructureGridBuilder, InvalidOptionsNameTheField) {
  StructureGridOptions options = Options(StructureGridOptions::METHOD_SLOPE);
  options.mutable_slope()->set_slammable_slope_deg(10.0);
  auto builder = StructureGridBuilder::Create(velodyne::DefaultLaserTable(velodyne::Model::kVlp16), options);
  ASSERT_FALSE(builder.ok());
  EXPECT_EQ(builder.error().message, "slope.slammable_slope_deg: must exceed slope.hazard_slope_deg");

  options = Options(StructureGridOptions::METHOD_POLAR_POPCOUNT);
  options.mutable_popcount()->set_polar_azimuth_bins(10);
  EXPECT_EQ(ValidateStructureGridOptions(options).error().message,
            "popcount.polar_azimuth_bins: must be at least 360");
  options = Options(StructureGridOptions::METHOD_SLOPE);
  options.set_resolution_m(0.0);
  EXPECT_EQ(ValidateStructureGridOptions(options).error().message, "resolution_m: must be positive and finite");
  options = Options(StructureGridOptions::METHOD_SLOPE);
  options.set_size_m(1000.0);
  EXPECT_EQ(ValidateStructureGridOptions(options).error().message,
            "size_m: gives more than 8192 cells per side at this resolution");
}

TEST(StructureGridConfig, ShippedConfigLoads) {
  const auto options = LoadStructureGridOptions(std::string(FLAT2D_SOURCE_DIR) +
                                                "/packaging/config/grid/structure_grid.textproto");
  ASSERT_TRUE(options.ok()) << options.error().message;
  EXPECT_DOUBLE_EQ(options->slope().hazard_slope_deg(), 15.0);
  EXPECT_DOUBLE_EQ(options->fill_in().max_gap_m(), 0.25);
}

TEST(StructureGridConfig, MountingOfInvertsVehicleFromSensor) {
  for (const auto& [x, y, z, roll, pitch, yaw] : std::vector<std::array<double, 6>>{
           {0.0, 0.0, 1.9, 0.0, 0.0, 0.0}, {0.8, -0.3, 1.6, 2.0, -3.0, 30.0}, {-1.2, 0.4, 2.2, -179.0, 89.0, -135.0}}) {
    SensorMounting mounting;
    mounting.set_x_m(x);
    mounting.set_y_m(y);
    mounting.set_z_m(z);
    mounting.set_roll_deg(roll);
    mounting.set_pitch_deg(pitch);
    mounting.set_yaw_deg(yaw);
    const SensorMounting back = MountingOf(VehicleFromSensor(mounting));
    EXPECT_NEAR(back.x_m(), x, 1e-12);
    EXPECT_NEAR(back.y_m(), y, 1e-12);
    EXPECT_NEAR(back.z_m(), z, 1e-12);
    EXPECT_NEAR(back.roll_deg(), roll, 1e-6);
    EXPECT_NEAR(back.pitch_deg(), pitch, 1e-6);
    EXPECT_NEAR(back.yaw_deg(), yaw, 1e-6);
  }
}

}  // namespace
}  // namespace flat2d::maps
