#include "maps/prior_map/prior_map_reader.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "maps/prior_map/prior_map_file.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps {
namespace {

std::filesystem::path Scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("flat2d_prior_map_" + name + "_" + std::to_string(::getpid()));
}

// 700 x 500 cells at 5 cm: free ground with walls, seeded clutter, and an empty east strip
// (whole tiles of unknown that the file must not store).
ClassGrid TestGrid() {
  ClassGrid grid(GridGeometry{.width = 700, .height = 500, .resolution_m = 0.05, .origin = Eigen::Vector2d(-12.5, 40.0)});
  std::mt19937 random(42);
  std::uniform_int_distribution<int> cls(0, 3);
  for (int row = 0; row < 500; ++row) {
    for (int col = 0; col < 560; ++col) {
      CellClass c = CellClass::kFree;
      if (row == 100 || col == 300) c = CellClass::kSlammable;
      if ((row * 7 + col * 13) % 97 == 0) c = static_cast<CellClass>(cls(random));
      grid.Mark(CellIndex{col, row}, c);
    }
  }
  return grid;
}

std::vector<std::uint8_t> ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

PriorMapWriteOptions Options() {
  PriorMapWriteOptions options;
  options.tile_cells = 64;
  options.created_utc = "2026-12-01T00:00:00Z";
  options.source = "test grid";
  options.georeference.mutable_enu()->set_latitude_deg(48.0125);
  options.georeference.mutable_enu()->set_longitude_deg(7.8345);
  return options;
}

TEST(PriorMapTest, RoundTripKeepsEveryCellAndTheHeader) {
  const ClassGrid grid = TestGrid();
  const auto path = Scratch("round_trip");
  ASSERT_TRUE(WritePriorMap(grid, path, Options()).ok());
  auto reader = PriorMapReader::Open(path, 4);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  const PriorMapHeader& h = reader->header();
  EXPECT_EQ(h.format_version(), kPriorMapFormatVersion);
  EXPECT_DOUBLE_EQ(h.resolution_m(), 0.05);
  EXPECT_EQ(h.tile_cells(), 64);
  EXPECT_EQ(h.width_tiles(), 11);   // ceil(700 / 64)
  EXPECT_EQ(h.height_tiles(), 8);   // ceil(500 / 64)
  EXPECT_DOUBLE_EQ(h.origin_x_m(), -12.5);
  EXPECT_DOUBLE_EQ(h.georeference().enu().latitude_deg(), 48.0125);
  EXPECT_EQ(h.legend().at(3), "slammable");
  EXPECT_EQ(h.mapped_cells(), grid.geometry().cell_count() - grid.Count(CellClass::kUnknown));
  EXPECT_GT(h.mapped_cells(), 270000u);
  // Columns 560-699 are unknown: tile column 9 (576-639) and 10 hold nothing.
  EXPECT_EQ(h.tiles_size(), 9 * 8);
  EXPECT_EQ(reader->file_bytes(), std::filesystem::file_size(path));
  for (int row = 0; row < 500; ++row) {
    for (int col = 0; col < 700; ++col) {
      const Eigen::Vector2d p = grid.geometry().CellCenter({col, row});
      ASSERT_EQ(reader->ClassAt(p), grid.at({col, row})) << col << ", " << row;
    }
  }
  EXPECT_EQ(reader->ClassAt({-100.0, 0.0}), CellClass::kUnknown);
  EXPECT_EQ(reader->stats().damaged_tiles, 0u);
  std::filesystem::remove(path);
}

TEST(PriorMapTest, CacheHoldsAtMostItsTilesAndEvictsTheLeastRecentlyUsed) {
  const auto path = Scratch("cache");
  ASSERT_TRUE(WritePriorMap(TestGrid(), path, Options()).ok());
  auto reader = PriorMapReader::Open(path, 2);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  for (const auto& [col, row] : {std::pair{0, 0}, {1, 0}, {0, 0}, {2, 0}, {0, 0}, {1, 0}}) {
    ASSERT_TRUE(reader->Tile(col, row).ok());
  }
  // 0,0 read; 1,0 read; 0,0 hit; 2,0 read evicting 1,0; 0,0 hit; 1,0 read evicting 2,0.
  EXPECT_EQ(reader->stats().tile_reads, 4u);
  EXPECT_EQ(reader->stats().cache_hits, 2u);
  EXPECT_EQ(reader->stats().evictions, 2u);
  std::filesystem::remove(path);
}

TEST(PriorMapTest, ReadingTilesAfterOpenAllocatesNothing) {
  const auto path = Scratch("alloc");
  ASSERT_TRUE(WritePriorMap(TestGrid(), path, Options()).ok());
  auto reader = PriorMapReader::Open(path, 3);
  ASSERT_TRUE(reader.ok());
  ASSERT_TRUE(reader->Tile(0, 0).ok());  // zstd sizes its workspace on the first frame
  const std::uint64_t before = testing::AllocationCount();
  for (int pass = 0; pass < 3; ++pass) {
    for (int row = 0; row < 8; ++row) {
      for (int col = 0; col < 11; ++col) ASSERT_TRUE(reader->Tile(col, row).ok());
    }
  }
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_GT(reader->stats().evictions, 100u);
  std::filesystem::remove(path);
}

TEST(PriorMapTest, DamagedFilesAreErrorsThatSayWhere) {
  const auto path = Scratch("damaged");
  ASSERT_TRUE(WritePriorMap(TestGrid(), path, Options()).ok());
  const std::vector<std::uint8_t> good = ReadBytes(path);
  auto open = [](std::vector<std::uint8_t> bytes) { return PriorMapReader::FromBytes(std::move(bytes), 4, "m"); };
  ASSERT_TRUE(open(good).ok());

  ASSERT_GT(good.size(), 1000u);
  std::vector<std::uint8_t> bytes = good;
  bytes.at(0) = 'X';
  EXPECT_NE(open(bytes).error().message.find("not a prior map"), std::string::npos);
  bytes = good;
  bytes.at(8) = 2;
  EXPECT_NE(open(bytes).error().message.find("format version 2"), std::string::npos);
  bytes = good;
  bytes.at(kPriorMapPreambleBytes + 3) ^= 0x40;
  EXPECT_NE(open(bytes).error().message.find("header CRC"), std::string::npos);
  bytes.assign(good.begin(), good.begin() + 10);
  EXPECT_NE(open(bytes).error().message.find("preamble"), std::string::npos);
  bytes.assign(good.begin(), good.end() - 100);  // the last tile loses its end
  EXPECT_NE(open(bytes).error().message.find("truncated"), std::string::npos);

  // A flipped bit inside a tile: that tile is an error naming it, its cells read unknown,
  // every other tile still reads.
  auto reader = open(good);
  const TileEntry& first = reader->header().tiles(0);
  bytes = good;
  const std::uint32_t header_bytes = static_cast<std::uint32_t>(bytes.at(12)) |
                                     static_cast<std::uint32_t>(bytes.at(13)) << 8 |
                                     static_cast<std::uint32_t>(bytes.at(14)) << 16 |
                                     static_cast<std::uint32_t>(bytes.at(15)) << 24;
  bytes.at(kPriorMapPreambleBytes + header_bytes + first.offset() + first.compressed_bytes() / 2) ^= 0x01;
  auto damaged = open(bytes);
  ASSERT_TRUE(damaged.ok());
  auto tile = damaged->Tile(first.col(), first.row());
  ASSERT_FALSE(tile.ok());
  EXPECT_NE(tile.error().message.find("tile (0, 0): CRC mismatch"), std::string::npos) << tile.error().message;
  EXPECT_EQ(damaged->ClassAt({-12.5 + 0.025, 40.0 + 0.025}), CellClass::kUnknown);
  EXPECT_EQ(damaged->stats().damaged_tiles, 2u);
  EXPECT_TRUE(damaged->Tile(1, 0).ok());
  std::filesystem::remove(path);
}

TEST(PriorMapTest, BadWriteOptionsAndMissingFiles) {
  ClassGrid grid(GridGeometry{.width = 10, .height = 10, .resolution_m = 0.05});
  PriorMapWriteOptions options;
  options.tile_cells = 8;
  EXPECT_FALSE(WritePriorMap(grid, Scratch("bad"), options).ok());
  EXPECT_FALSE(PriorMapReader::Open("/nonexistent/map.f2dmap").ok());
  EXPECT_FALSE(PriorMapReader::FromBytes({}, 0, "m").ok());
}

}  // namespace
}  // namespace flat2d::maps
