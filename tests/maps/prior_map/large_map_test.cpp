// A city-sized map in fixed memory (issue 8 acceptance): a 1 km x 1 km map at 5 cm (400 M
// cells, 6241 tiles of 256^2), written tile by tile from a procedural city of blocks, read
// with a 16-tile cache while a trajectory crosses it corner to corner and back. The process's
// resident memory may grow by the cache and the index, not by the map.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "maps/prior_map/prior_map_file.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::maps {
namespace {

constexpr int kSideCells = 20000;  // 1 km at 5 cm

// Blocks 40 m apart: a building wall 2 cells thick every 40 m in x and y, streets free.
class CityTiles final : public TileSource {
 public:
  CityTiles() : geometry_{kSideCells, kSideCells, 0.05, Eigen::Vector2d(-500.0, -500.0)} {}
  const GridGeometry& geometry() const override { return geometry_; }
  bool FillTile(int n, int tile_col, int tile_row, std::span<std::uint8_t> cells) override {
    for (int r = 0; r < n; ++r) {
      const int row = tile_row * n + r;
      for (int c = 0; c < n; ++c) {
        const int col = tile_col * n + c;
        CellClass value = CellClass::kUnknown;
        if (row < kSideCells && col < kSideCells) {
          value = (row % 800 < 2 || col % 800 < 2) ? CellClass::kSlammable : CellClass::kFree;
        }
        cells[static_cast<std::size_t>(r * n + c)] = static_cast<std::uint8_t>(value);
      }
    }
    return true;
  }

 private:
  GridGeometry geometry_;
};

// Resident set size from /proc/self/statm, bytes.
std::size_t ResidentBytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long size = 0, resident = 0;
  const int read = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return read == 2 ? resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)) : 0;
}

TEST(LargeMap, A1km2MapIsCrossedInFixedMemory) {
  const auto path = std::filesystem::temp_directory_path() / ("flat2d_large_map_" + std::to_string(::getpid()));
  CityTiles city;
  PriorMapWriteOptions options;
  options.zstd_level = 1;  // the test's time, not the file's size
  ASSERT_TRUE(WritePriorMap(city, path, options).ok());

  auto reader = PriorMapReader::Open(path, 16);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_EQ(reader->header().tiles_size(), 79 * 79);
  EXPECT_NEAR(static_cast<double>(reader->header().mapped_cells()) * 0.0025, 1e6, 1.0);  // 1 km^2

  // Corner to corner and back, a query every 5 cm along the way and 20 m either side.
  const std::size_t before = ResidentBytes();
  std::size_t peak = before;
  std::size_t slammable = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i <= 28000; ++i) {
      const double s = (pass == 0 ? i : 28000 - i) / 28000.0;
      const Eigen::Vector2d p(-495.0 + 990.0 * s, -495.0 + 990.0 * s);
      for (double lateral : {-20.0, 0.0, 20.0}) {
        slammable += reader->ClassAt(p + Eigen::Vector2d(lateral, -lateral)) == CellClass::kSlammable;
      }
      if (i % 1000 == 0) peak = std::max(peak, ResidentBytes());
    }
  }
  peak = std::max(peak, ResidentBytes());
  std::filesystem::remove(path);

  EXPECT_GT(slammable, 100u);  // walls were crossed
  EXPECT_GT(reader->stats().tile_reads, 500u);
  EXPECT_GT(reader->stats().evictions, 400u);
  EXPECT_EQ(reader->stats().damaged_tiles, 0u);
  // The cache is 16 x 64 KiB = 1 MiB; nothing else may grow while crossing.
  std::printf("resident: %.1f MiB after Open, %.1f MiB peak while crossing; %llu tile reads\n",
              static_cast<double>(before) / (1 << 20), static_cast<double>(peak) / (1 << 20),
              static_cast<unsigned long long>(reader->stats().tile_reads));
  EXPECT_LT(peak - before, std::size_t{2} << 20);
}

}  // namespace
}  // namespace flat2d::maps
