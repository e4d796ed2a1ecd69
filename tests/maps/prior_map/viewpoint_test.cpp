// Viewpoint sub-maps: what VisibleFrom keeps, and their round trip through the map file.
#include "maps/prior_map/viewpoint.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "maps/prior_map/prior_map_file.hpp"
#include "maps/prior_map/prior_map_reader.hpp"
#include "maps/prior_map/prior_map_region.hpp"
#include "maps/prior_map/prior_map_summary.hpp"

namespace flat2d::maps {
namespace {

std::filesystem::path Scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("flat2d_viewpoint_" + name + "_" + std::to_string(::getpid()));
}

// 20 x 10 m of free floor at 5 cm, a wall across x = 10 m from y = 2 to 8 m.
ClassGrid Floor() {
  ClassGrid grid(GridGeometry{.width = 400, .height = 200, .resolution_m = 0.05, .origin = Eigen::Vector2d(0, 0)});
  for (int row = 0; row < 200; ++row) {
    for (int col = 0; col < 400; ++col) grid.Mark(CellIndex{col, row}, CellClass::kFree);
  }
  for (int row = 40; row < 160; ++row) grid.Mark(CellIndex{200, row}, CellClass::kSlammable);
  return grid;
}

TEST(Viewpoint, KeepsWhatThePoseSeesAndNotWhatTheWallHides) {
  const ClassGrid floor = Floor();
  const ClassGrid visible = VisibleFrom(floor, {5.0, 5.0}, 12.0);
  // Aligned with the mosaic: its origin is on the mosaic's cell corners.
  EXPECT_NEAR(std::fmod(visible.geometry().origin.x() + 1e-9, 0.05), 0.0, 1e-6);
  auto at = [&](double x, double y) {
    const auto cell = visible.geometry().CellOf({x, y});
    return cell ? visible.at(*cell) : CellClass::kUnknown;
  };
  EXPECT_EQ(at(8.0, 5.0), CellClass::kFree);         // in front of the wall
  EXPECT_EQ(at(10.025, 5.0), CellClass::kSlammable);  // the wall's face
  EXPECT_EQ(at(12.0, 5.0), CellClass::kUnknown);      // behind it
  EXPECT_EQ(at(12.0, 9.5), CellClass::kFree);         // past its end, in view
  EXPECT_EQ(at(1.0, 1.0), CellClass::kFree);
  EXPECT_GT(visible.Count(CellClass::kSlammable), 100u);
}

TEST(Viewpoint, RoundTripsThroughTheMapFileAndDamageIsNamed) {
  const ClassGrid floor = Floor();
  std::vector<ViewpointGrid> viewpoints;
  viewpoints.push_back({5.0, 5.0, 0.3, 12.5, VisibleFrom(floor, {5.0, 5.0}, 6.0)});
  viewpoints.push_back({15.0, 5.0, -1.0, 20.0, VisibleFrom(floor, {15.0, 5.0}, 4.0)});
  PriorMapWriteOptions options;
  options.tile_cells = 64;
  const auto path = Scratch("round_trip");
  ASSERT_TRUE(WritePriorMap(floor, path, options, viewpoints).ok());

  auto reader = PriorMapReader::Open(path, 2);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  ASSERT_EQ(reader->viewpoint_count(), 2);
  EXPECT_DOUBLE_EQ(reader->header().viewpoints(0).yaw_rad(), 0.3);
  EXPECT_DOUBLE_EQ(reader->header().viewpoints(1).time_s(), 20.0);
  for (int i = 0; i < 2; ++i) {
    auto grid = reader->ViewpointGrid(i);
    ASSERT_TRUE(grid.ok()) << grid.error().message;
    const ClassGrid& expected = viewpoints[static_cast<std::size_t>(i)].cells;
    ASSERT_EQ(grid->geometry().width, expected.geometry().width);
    ASSERT_EQ(grid->geometry().height, expected.geometry().height);
    EXPECT_NEAR((grid->geometry().origin - expected.geometry().origin).norm(), 0.0, 1e-9);
    EXPECT_TRUE(std::equal(grid->cells().begin(), grid->cells().end(), expected.cells().begin()));
  }
  EXPECT_FALSE(reader->ViewpointCells(2).ok());

  const PriorMapSummary summary = SummarizePriorMap(*reader);
  EXPECT_EQ(summary.viewpoints, 2);
  EXPECT_NEAR(summary.mapped_area_m2, 200.0, 1e-6);  // 20 x 10 m, every cell observed
  EXPECT_NEAR(summary.slammable_area_m2, 120 * 0.0025, 1e-9);
  EXPECT_EQ(summary.file_bytes, std::filesystem::file_size(path));
  EXPECT_GT(summary.viewpoint_bytes, 0u);
  EXPECT_NE(SummaryJson(summary).find("\"mapped_area_m2\":200.000"), std::string::npos) << SummaryJson(summary);

  // The last bytes of the file are the second viewpoint's: damage there is named.
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  bytes[bytes.size() - 3] ^= 0x10;
  auto damaged = PriorMapReader::FromBytes(bytes, 2, "m");
  ASSERT_TRUE(damaged.ok());
  auto cells = damaged->ViewpointCells(1);
  ASSERT_FALSE(cells.ok());
  EXPECT_NE(cells.error().message.find("viewpoint 1: CRC mismatch"), std::string::npos) << cells.error().message;
  EXPECT_TRUE(damaged->ViewpointCells(0).ok());
  bytes.resize(bytes.size() - 5);
  auto truncated = PriorMapReader::FromBytes(bytes, 2, "m");
  ASSERT_FALSE(truncated.ok());
  EXPECT_NE(truncated.error().message.find("viewpoint 1"), std::string::npos) << truncated.error().message;
  std::filesystem::remove(path);
}

TEST(PriorMapRegion, ReadsTheCellsOfABoxAndRefusesOneOffTheMap) {
  const ClassGrid floor = Floor();
  PriorMapWriteOptions options;
  options.tile_cells = 64;
  const auto path = Scratch("region");
  ASSERT_TRUE(WritePriorMap(floor, path, options).ok());
  auto reader = PriorMapReader::Open(path, 2);
  ASSERT_TRUE(reader.ok());
  auto extent = StoredExtent(*reader);
  ASSERT_TRUE(extent.has_value());
  EXPECT_NEAR(extent->high.x(), 7 * 64 * 0.05, 1e-9);  // whole tiles
  auto region = ReadRegion(*reader, {{9.0, 1.0}, {11.0, 9.0}});
  ASSERT_TRUE(region.ok()) << region.error().message;
  EXPECT_EQ(region->geometry().width, 40);
  EXPECT_EQ(region->geometry().height, 160);
  EXPECT_EQ(region->Count(CellClass::kSlammable), 120u);
  EXPECT_EQ(region->Count(CellClass::kUnknown), 0u);
  EXPECT_FALSE(ReadRegion(*reader, {{100.0, 100.0}, {110.0, 110.0}}).ok());
  EXPECT_FALSE(ReadRegion(*reader, {{0.0, 0.0}, {20.0, 10.0}}, 1000).ok());  // too many cells
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace flat2d::maps
