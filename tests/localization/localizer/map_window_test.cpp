// The map window: the prior map's slammable cells around a position, cell for cell, read
// through the reader's cache; moved only when the vehicle has gone recentre_m; empty off the
// map; a damaged tile an error naming it.
#include "localization/localizer/map_window.hpp"
#include "localization/localizer/map_prefetch.hpp"

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

// The prefetch worker's window and score table are those a synchronous move would have made;
// taking them hands the matcher the new map and keeps the old one as the next spare.
TEST_F(MapWindowTest, APrefetchedWindowIsTheOneAMoveWouldFill) {
  auto map = maps::PriorMapReader::Open(path_, 8);
  ASSERT_TRUE(map.ok());
  const MapWindowOptions options{.side_m = 20.0, .recentre_m = 4.0};
  auto window = MapWindow::Create(*map, options);
  auto spare = MapWindow::Create(*map, options);
  auto reference = MapWindow::Create(*map, options);
  ASSERT_TRUE(window.ok() && spare.ok() && reference.ok());
  const MatcherLimits limits{.max_map_cells = window->grid().geometry().CellCount()};
  CorrelativeMatcher matcher(limits, {});
  CorrelativeMatcher reference_matcher(limits, {});
  ASSERT_TRUE(*window->Cover(*map, {5.0, 55.0}));
  ASSERT_TRUE(matcher.SetMap(window->grid()).ok());
  const std::uint8_t* first_table = matcher.table().data();

  MapPrefetch prefetch(std::move(*spare), matcher.NewMap());
  EXPECT_TRUE(prefetch.idle());
  const Eigen::Vector2d next(9.0, 55.0);
  prefetch.Start(*map, next);
  EXPECT_FALSE(prefetch.idle());
  ASSERT_TRUE(prefetch.Finish().ok());
  EXPECT_EQ(prefetch.centre(), next);
  EXPECT_GT(prefetch.last_job_cpu_s(), 0.0);
  prefetch.Take(*window, matcher);
  EXPECT_TRUE(prefetch.idle());

  ASSERT_TRUE(*reference->Cover(*map, next));
  ASSERT_TRUE(reference_matcher.SetMap(reference->grid()).ok());
  EXPECT_EQ(window->centre(), next);
  const GridGeometry& g = window->grid().geometry();
  ASSERT_EQ(g.origin, reference->grid().geometry().origin);
  ASSERT_NE(matcher.table().data(), first_table);  // the spare's table, not a copy
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      ASSERT_EQ(window->grid().Occupied(x, y), reference->grid().Occupied(x, y)) << x << ", " << y;
      ASSERT_EQ(matcher.table().At(x, y), reference_matcher.table().At(x, y)) << x << ", " << y;
    }
  }
  // The next job fills the old window, now the spare, while the matcher keeps the new one.
  prefetch.Start(*map, {13.0, 55.0});
  ASSERT_TRUE(prefetch.Finish().ok());
  prefetch.Discard();
  EXPECT_EQ(window->centre(), next);
}

TEST_F(MapWindowTest, APrefetchOfADamagedTileReportsIt) {
  std::vector<std::uint8_t> damaged = ReadBytes(path_);
  damaged[damaged.size() - 100] ^= 0x5a;
  auto map = maps::PriorMapReader::FromBytes(damaged, 8, "damaged.f2m");
  ASSERT_TRUE(map.ok());
  auto spare = MapWindow::Create(*map, {.side_m = 60.0, .recentre_m = 4.0});
  ASSERT_TRUE(spare.ok());
  CorrelativeMatcher matcher({.max_map_cells = spare->grid().geometry().CellCount()}, {});
  MapPrefetch prefetch(std::move(*spare), matcher.NewMap());
  prefetch.Start(*map, {10.0, 57.0});
  const Status status = prefetch.Finish();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("damaged.f2m"), std::string::npos) << status.error().message;
  prefetch.Discard();
  EXPECT_TRUE(prefetch.idle());
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
