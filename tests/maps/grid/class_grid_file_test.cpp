#include "maps/grid/class_grid_file.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "hal/mapfile/map_server.hpp"

namespace flat2d::maps {
namespace {

TEST(ClassGridFile, RoundTripKeepsClassesAndGeometry) {
  ClassGrid grid(GridGeometry{.width = 5, .height = 4, .resolution_m = 0.05, .origin = Eigen::Vector2d(-1.0, 2.5)});
  grid.Mark(CellIndex{0, 0}, CellClass::kSlammable);
  grid.Mark(CellIndex{4, 3}, CellClass::kHazard);
  grid.Mark(CellIndex{2, 1}, CellClass::kFree);
  const auto stem = std::filesystem::temp_directory_path() / "flat2d_class_grid_file_test";
  ASSERT_TRUE(WriteClassGrid(grid, stem).ok());
  // map_server's view: row 0 (lowest y) is the image's last row.
  const auto gray = hal::mapfile::ReadMapServer(stem.string() + ".yaml");
  ASSERT_TRUE(gray.ok());
  EXPECT_EQ(gray->pixels[3 * 5 + 0], kSlammableGray);
  EXPECT_EQ(gray->pixels[0 * 5 + 4], kHazardGray);
  EXPECT_EQ(gray->pixels[1 * 5 + 1], kUnknownGray);
  const auto read = ReadClassGrid(stem.string() + ".yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->geometry().width, 5);
  EXPECT_EQ(read->geometry().origin, Eigen::Vector2d(-1.0, 2.5));
  EXPECT_TRUE(std::equal(read->cells().begin(), read->cells().end(), grid.cells().begin(), grid.cells().end()));
  std::filesystem::remove(stem.string() + ".yaml");
  std::filesystem::remove(stem.string() + ".pgm");
}

TEST(ClassGridFile, OtherGraysFollowMapServerThresholds) {
  EXPECT_EQ(ClassOfGray(10), CellClass::kSlammable);   // darkness 0.96
  EXPECT_EQ(ClassOfGray(255), CellClass::kFree);
  EXPECT_EQ(ClassOfGray(100), CellClass::kUnknown);    // darkness 0.61: between thresholds
  EXPECT_EQ(ClassOfGray(kHazardGray), CellClass::kHazard);
}

}  // namespace
}  // namespace flat2d::maps
