// The map window: the prior map's slammable cells around a position, cell for cell, read
// through the reader's cache; moved only when the vehicle has gone recentre_m; empty off the
// map; a damaged tile an error naming it.
#include "localization/localizer/map_window.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "maps/prior_map/prior_map_file.hpp"
#include "maps/prior_map/viewpoint.hpp"

namespace flat2d::localization {
namespace {

std::filesystem::path Scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("flat2d_map_window_" + name + "_" + std::to_string(::getpid()));
}

std::vector<std::uint8_t> ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// 900 x 700 cells at 5 cm (45 x 35 m), seeded classes, origin off the tile grid's multiples.
maps::ClassGrid TestGrid() {
  maps::ClassGrid grid(maps::GridGeometry{.width = 900, .height = 700, .resolution_m = 0.05,
                                          .origin = Eigen::Vector2d(-12.35, 40.1)});
  std::mt19937 random(7);
  std::uniform_int_distribution<int> cls(0, 3);
  for (int row = 0; row < 700; ++row) {
    for (int col = 0; col < 900; ++col) grid.Mark(maps::CellIndex{col, row}, static_cast<maps::CellClass>(cls(random)));
  }
  return grid;
}

class MapWindowTest : public ::testing::Test {
 protected:
  MapWindowTest() : path_(Scratch("map")), grid_(TestGrid()) {
    maps::PriorMapWriteOptions options;
    options.tile_cells = 64;
    options.created_utc = "2026-12-01T00:00:00Z";
    EXPECT_TRUE(maps::WritePriorMap(grid_, path_, options).ok());
  }
  ~MapWindowTest() override { std::filesystem::remove(path_); }

  std::filesystem::path path_;
  maps::ClassGrid grid_;
};

TEST_F(MapWindowTest, HoldsTheMapsSlammableCellsAroundThePosition) {
  auto map = maps::PriorMapReader::Open(path_, 8);
  ASSERT_TRUE(map.ok()) << map.error().message;
  auto window = MapWindow::Create(*map, {.side_m = 20.0, .recentre_m = 4.0});
  ASSERT_TRUE(window.ok()) << window.error().message;
  // Near the map's south-west corner, so part of the window is off the map.
  const Eigen::Vector2d position(-8.0, 43.0);
  auto moved = window->Cover(*map, position);
  ASSERT_TRUE(moved.ok() && *moved);
  const GridGeometry& g = window->grid().geometry();
  EXPECT_EQ(g.width, 400);
  EXPECT_LE((g.origin + Eigen::Vector2d(10.0, 10.0) - position).cwiseAbs().maxCoeff(), 0.05 + 1e-9);
  int structure = 0, off_map = 0;
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const Eigen::Vector2d centre = g.CellCenter(x, y);
      const auto cell = grid_.geometry().CellOf(centre);
      const bool slammable = cell && grid_.at(*cell) == maps::CellClass::kSlammable;
      ASSERT_EQ(window->grid().Occupied(x, y), slammable) << x << ", " << y;
      structure += slammable ? 1 : 0;
      off_map += cell ? 0 : 1;
    }
  }
  EXPECT_GT(structure, 15'000);  // a quarter of the 74,000 cells on the map
  EXPECT_GT(off_map, 10'000);
}

TEST_F(MapWindowTest, MovesOnlyWhenTheVehicleHasLeftItsCentre) {
  auto map = maps::PriorMapReader::Open(path_, 8);
  ASSERT_TRUE(map.ok());
  auto window = MapWindow::Create(*map, {.side_m = 20.0, .recentre_m = 4.0});
  ASSERT_TRUE(window.ok());
  EXPECT_TRUE(*window->Cover(*map, {5.0, 55.0}));
  EXPECT_FALSE(*window->Cover(*map, {8.5, 55.0}));
  EXPECT_FALSE(*window->Cover(*map, {5.0, 51.1}));
  EXPECT_TRUE(*window->Cover(*map, {9.1, 55.0}));
  EXPECT_EQ(window->centre(), Eigen::Vector2d(9.1, 55.0));
  EXPECT_TRUE(*window->Cover(*map, {9.6, 55.0}, 0.5));  // a global search wants it centred
  EXPECT_EQ(window->moves(), 3u);
  // Entirely off the map: an empty window, not an error.
  EXPECT_TRUE(*window->Cover(*map, {500.0, -500.0}));
  EXPECT_EQ(window->grid().OccupiedCount(), 0u);
}

TEST_F(MapWindowTest, ADamagedTileIsAnErrorNamingIt) {
  std::vector<std::uint8_t> damaged = ReadBytes(path_);
  damaged[damaged.size() - 100] ^= 0x5a;  // inside the last stored tile's frame
  auto map = maps::PriorMapReader::FromBytes(damaged, 8, "damaged.f2m");
  ASSERT_TRUE(map.ok()) << map.error().message;
  auto window = MapWindow::Create(*map, {.side_m = 60.0, .recentre_m = 4.0});
  ASSERT_TRUE(window.ok());
  auto moved = window->Cover(*map, {10.0, 57.0});  // the window spans the whole map
  ASSERT_FALSE(moved.ok());
  EXPECT_NE(moved.error().message.find("damaged.f2m"), std::string::npos) << moved.error().message;
  EXPECT_NE(moved.error().message.find("tile"), std::string::npos) << moved.error().message;
  EXPECT_FALSE(window->filled());
}

// Viewpoint mode: the nearest viewpoint's visible cells, switched only when another is
// nearer by the margin; a map without viewpoints leaves the window as it is.
TEST_F(MapWindowTest, FollowsTheNearestViewpoint) {
  const auto path = Scratch("viewpoints");
  std::vector<maps::ViewpointGrid> viewpoints;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.0, 50.0), Eigen::Vector2d(10.0, 50.0)}) {
    viewpoints.push_back({p.x(), p.y(), 0.0, 0.0, maps::VisibleFrom(grid_, p, 8.0)});
  }
  maps::PriorMapWriteOptions options;
  options.tile_cells = 64;
  options.created_utc = "2026-12-01T00:00:00Z";
  ASSERT_TRUE(maps::WritePriorMap(grid_, path, options, viewpoints).ok());
  auto map = maps::PriorMapReader::Open(path, 8);
  ASSERT_TRUE(map.ok()) << map.error().message;
  auto window = MapWindow::Create(*map, {.side_m = 20.0, .recentre_m = 4.0});
  ASSERT_TRUE(window.ok());

  EXPECT_TRUE(*window->CoverWithViewpoint(*map, {1.0, 49.0}));
  EXPECT_EQ(window->viewpoint(), 0);
  // Cell for cell the viewpoint's slammable cells, nothing else.
  const maps::ClassGrid& visible = viewpoints[0].cells;
  const GridGeometry& g = window->grid().geometry();
  std::size_t expected = 0;
  for (int row = 0; row < visible.geometry().height; ++row) {
    for (int col = 0; col < visible.geometry().width; ++col) {
      if (visible.at({col, row}) != maps::CellClass::kSlammable) continue;
      ++expected;
      const Eigen::Vector2d centre = visible.geometry().CellCenter({col, row});
      const Eigen::Vector2i cell = g.CellOf(centre);
      EXPECT_TRUE(window->grid().Occupied(cell.x(), cell.y())) << col << ", " << row;
    }
  }
  EXPECT_GT(expected, 10u);  // rays stop at the first slammable cell: a quarter of the cells are
  EXPECT_EQ(window->grid().OccupiedCount(), expected);

  EXPECT_FALSE(*window->CoverWithViewpoint(*map, {5.4, 50.0}));  // nearer the second, by < 1 m
  EXPECT_TRUE(*window->CoverWithViewpoint(*map, {6.0, 50.0}));
  EXPECT_EQ(window->viewpoint(), 1);
  EXPECT_TRUE(*window->Cover(*map, {6.0, 50.0}, 0.0));  // back to the mosaic
  EXPECT_EQ(window->viewpoint(), -1);
  std::filesystem::remove(path);

  auto plain = maps::PriorMapReader::Open(path_, 8);  // the fixture's map has no viewpoints
  ASSERT_TRUE(plain.ok());
  EXPECT_FALSE(*window->CoverWithViewpoint(*plain, {6.0, 50.0}));
}

TEST(MapWindowOptions, RejectsAWindowItCannotRecentreIn) {
  EXPECT_TRUE(ValidateOptions(MapWindowOptions{}).ok());
  EXPECT_FALSE(ValidateOptions({.side_m = 0.0, .recentre_m = 1.0}).ok());
  EXPECT_FALSE(ValidateOptions({.side_m = 20.0, .recentre_m = 10.0}).ok());
  EXPECT_FALSE(ValidateOptions({.side_m = 20.0, .recentre_m = -1.0}).ok());
}

}  // namespace
}  // namespace flat2d::localization
