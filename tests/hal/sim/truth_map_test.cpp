// The truth map of a scene with each kind of structure: occupied footprints exact to one
// cell, low obstacles and steep ramps as hazard, gentle ramps and overhead things free,
// moving objects absent; the PGM/YAML pair read back with its origin and resolution.
#include "hal/sim/truth_map.hpp"

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/hal/sim/scene_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::MakeScene;

const char* kScene = R"(
  boxes { center { x: 10 y: 10 } length_m: 2 width_m: 2 height_m: 1 }
  boxes { center { x: 40 y: 10 } length_m: 1 width_m: 1 height_m: 0.1 }
  walls { points { x: 0 y: 20 } points { x: 20 y: 20 } thickness_m: 0.2 height_m: 2 }
  cylinders { center { x: 30 y: 10 } radius_m: 0.5 height_m: 3 }
  curbs { points { x: 0 y: 0 } points { x: 20 y: 0 } height_m: 0.15 width_m: 0.3 }
  bars { a { x: 25 y: 20 } b { x: 35 y: 20 } z: 1 thickness_m: 0.03 }
  bars { a { x: 25 y: 24 } b { x: 35 y: 24 } z: 3 thickness_m: 0.1 }
  foliage { center { x: 45 y: 20 } radius_m: 2 bottom: 2.5 top: 7 density_per_m: 1 }
  foliage { center { x: 45 y: 30 } radius_m: 1 bottom: 0 top: 1.5 density_per_m: 3 }
  ground { ramps { start { x: 0 y: 30 } heading: 0 run_m: 5 width_m: 3 slope_deg: 16
                   plateau_m: 2 descend: true }
           ramps { start { x: 15 y: 30 } heading: 0 run_m: 5 width_m: 3 slope_deg: 14.5 }
           ramps { start { x: 30 y: 30 } heading: 0 run_m: 5 width_m: 3 slope_deg: 10 } }
  movers { box { length_m: 4 width_m: 2 height_m: 1.5 } path { x: 0 y: 33 }
           path { x: 50 y: 33 } speed_mps: 5 }
)";

constexpr double kResolution = 0.05;

// Rasterized once for all tests (a million cells; slow under the sanitizers).
const TruthMap& Rasterize() {
  static const TruthMap map = [] {
    const Scene scene = MakeScene(kScene);
    Result<TruthMap> result = RasterizeTruthMap(scene, {});
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
    return result.ok() ? std::move(result).value() : TruthMap{};
  }();
  return map;
}

// Over the cells around a footprint: centres inside (per `inside`) must have `expected`;
// centres more than one cell from it (per `distance`) must not.
void ExpectFootprint(const TruthMap& map, const Eigen::AlignedBox2d& around, TruthClass expected,
                     const std::function<double(const Eigen::Vector2d&)>& distance) {
  int inside = 0;
  for (int row = 0; row < map.height; ++row) {
    for (int col = 0; col < map.width; ++col) {
      const Eigen::Vector2d c = map.CellCenter(col, row);
      if (!around.contains(c)) continue;
      const double d = distance(c);  // <= 0 inside
      if (d <= 0.0) {
        ++inside;
        EXPECT_EQ(map.At(col, row), expected) << "cell centre " << c.transpose();
      } else if (d > kResolution) {
        EXPECT_NE(map.At(col, row), expected) << "cell centre " << c.transpose();
      }
    }
  }
  EXPECT_GT(inside, 0);
}

double BoxDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d outside = (lo - p).cwiseMax(p - hi);
  return outside.maxCoeff() > 0.0 ? outside.cwiseMax(0.0).norm() : outside.maxCoeff();
}

TEST(TruthMapTest, OccupiedFootprintsExactToOneCell) {
  const TruthMap& map = Rasterize();
  EXPECT_DOUBLE_EQ(map.resolution_m, kResolution);
  const auto box = [](Eigen::Vector2d lo, Eigen::Vector2d hi) {
    return [lo, hi](const Eigen::Vector2d& p) { return BoxDistance(p, lo, hi); };
  };
  ExpectFootprint(map, {Eigen::Vector2d(8, 8), Eigen::Vector2d(12, 12)}, TruthClass::kOccupied,
                  box({9, 9}, {11, 11}));
  ExpectFootprint(map, {Eigen::Vector2d(-1, 19), Eigen::Vector2d(21, 21)}, TruthClass::kOccupied,
                  box({0, 19.9}, {20, 20.1}));
  ExpectFootprint(map, {Eigen::Vector2d(29, 9), Eigen::Vector2d(31, 11)}, TruthClass::kOccupied,
                  [](const Eigen::Vector2d& p) { return (p - Eigen::Vector2d(30, 10)).norm() - 0.5; });
  // A 3 cm rail at 1 m marks the cells it runs through, as a hazard: it stands 3 cm tall,
  // so a LiDAR's fan holds one return of it at most, never a face.
  EXPECT_EQ(map.ClassAt(30.0, 20.0), TruthClass::kHazard);
  EXPECT_EQ(map.ClassAt(30.0, 20.1), TruthClass::kFree);
  // A hedge from the ground is structure; a crown from 2.5 m and a rail at 3 m are overhead.
  EXPECT_EQ(map.ClassAt(45.0, 30.0), TruthClass::kOccupied);
  EXPECT_EQ(map.ClassAt(45.0, 20.0), TruthClass::kFree);
  EXPECT_EQ(map.ClassAt(30.0, 24.0), TruthClass::kFree);
  // Moving objects are not part of the truth.
  EXPECT_EQ(map.ClassAt(0.0, 33.0), TruthClass::kFree);
}

TEST(TruthMapTest, LowObstaclesAndSteepGroundAreHazards) {
  const TruthMap& map = Rasterize();
  const auto box = [](Eigen::Vector2d lo, Eigen::Vector2d hi) {
    return [lo, hi](const Eigen::Vector2d& p) { return BoxDistance(p, lo, hi); };
  };
  ExpectFootprint(map, {Eigen::Vector2d(-1, -1), Eigen::Vector2d(21, 1)}, TruthClass::kHazard,
                  box({0, -0.15}, {20, 0.15}));
  ExpectFootprint(map, {Eigen::Vector2d(39, 9), Eigen::Vector2d(41, 11)}, TruthClass::kHazard,
                  box({39.5, 9.5}, {40.5, 10.5}));
  // Inside each ramp, two cells clear of its edges and slope breaks.
  const double m = 2 * kResolution;
  const auto ramp_cells = [&](double x0, double x1, TruthClass expected) {
    for (double x = x0 + m; x < x1 - m; x += kResolution) {
      for (double y = 28.5 + m; y < 31.5 - m; y += kResolution) {
        ASSERT_EQ(map.ClassAt(x, y), expected) << "at " << x << ", " << y;
      }
    }
  };
  ramp_cells(0, 5, TruthClass::kHazard);    // 16 deg rise
  ramp_cells(5, 7, TruthClass::kFree);      // its plateau
  ramp_cells(7, 12, TruthClass::kHazard);   // 16 deg fall
  ramp_cells(15, 20, TruthClass::kFree);    // 14.5 deg, below the 15 deg cutoff
  ramp_cells(30, 35, TruthClass::kFree);    // 10 deg
  // The 14.5 deg ramp ends in a drop-off of 5 tan(14.5) = 1.29 m: a hazard line.
  EXPECT_EQ(map.ClassAt(20.0 - 0.01, 30.0), TruthClass::kHazard);
  EXPECT_EQ(map.ClassAt(20.0 + 0.01, 30.0), TruthClass::kHazard);
  EXPECT_EQ(map.ClassAt(20.3, 30.0), TruthClass::kFree);
}

struct Pgm {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
};

Pgm ReadPgm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int max_value = 0;
  Pgm pgm;
  in >> magic >> pgm.width >> pgm.height >> max_value;
  EXPECT_EQ(magic, "P5");
  EXPECT_EQ(max_value, 255);
  in.get();  // the single whitespace before the raster
  pgm.pixels.resize(static_cast<std::size_t>(pgm.width) * static_cast<std::size_t>(pgm.height));
  in.read(reinterpret_cast<char*>(pgm.pixels.data()), static_cast<std::streamsize>(pgm.pixels.size()));
  EXPECT_TRUE(in.good());
  EXPECT_EQ(in.peek(), std::char_traits<char>::eof());
  return pgm;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double YamlNumber(const std::string& yaml, const std::string& key) {
  const auto at = yaml.find("\n" + key + ": ");
  EXPECT_NE(at, std::string::npos) << key;
  return std::stod(yaml.substr(at + key.size() + 3));
}

TEST(TruthMapTest, PgmAndYamlReadBack) {
  const TruthMap& map = Rasterize();
  const auto dir = std::filesystem::temp_directory_path() / "flat2d_truth_map_test";
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(WriteTruthMap(map, dir).ok());
  const Pgm pgm = ReadPgm(dir / "truth_map.pgm");
  ASSERT_EQ(pgm.width, map.width);
  ASSERT_EQ(pgm.height, map.height);
  const std::string yaml = ReadText(dir / "truth_map.yaml");
  EXPECT_NE(yaml.find("\nimage: truth_map.pgm\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("\nmode: trinary\n"), std::string::npos);
  EXPECT_NE(yaml.find("\nnegate: 0\n"), std::string::npos);
  EXPECT_NE(yaml.find("128 = hazard"), std::string::npos);
  EXPECT_DOUBLE_EQ(YamlNumber(yaml, "resolution"), kResolution);
  EXPECT_DOUBLE_EQ(YamlNumber(yaml, "occupied_thresh"), 0.65);
  EXPECT_DOUBLE_EQ(YamlNumber(yaml, "free_thresh"), 0.196);
  const auto origin_at = yaml.find("\norigin: [");
  ASSERT_NE(origin_at, std::string::npos);
  double ox = 0.0;
  double oy = 0.0;
  char comma = 0;
  std::istringstream(yaml.substr(origin_at + 10)) >> ox >> comma >> oy;
  // The scene's bounds start at the curb (x = 0, y = -0.15), less the 2 m margin.
  EXPECT_NEAR(ox, -2.0, 1e-12);
  EXPECT_NEAR(oy, -2.15, 1e-12);
  EXPECT_DOUBLE_EQ(ox, map.origin.x());
  EXPECT_DOUBLE_EQ(oy, map.origin.y());
  // Pixels by world position, the way map_server reads them: row 0 is the largest y.
  const auto pixel = [&](double x, double y) {
    const int col = static_cast<int>(std::floor((x - ox) / kResolution));
    const int row = pgm.height - 1 - static_cast<int>(std::floor((y - oy) / kResolution));
    return pgm.pixels[static_cast<std::size_t>(row) * static_cast<std::size_t>(pgm.width) +
                      static_cast<std::size_t>(col)];
  };
  EXPECT_EQ(pixel(10, 10), kTruthOccupiedGray);
  EXPECT_EQ(pixel(10, 0), kTruthHazardGray);
  EXPECT_EQ(pixel(10, 5), kTruthFreeGray);
  EXPECT_EQ(pixel(30, 10.4), kTruthOccupiedGray);

  ASSERT_TRUE(WriteTruthMap(map, dir / "custom").ok());  // a stem, not a directory
  EXPECT_TRUE(std::filesystem::exists(dir / "custom.pgm"));
  EXPECT_NE(ReadText(dir / "custom.yaml").find("image: custom.pgm"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(TruthMapTest, BadOptionsAndEmptyScenesAreErrors) {
  const Scene scene = MakeScene(kScene);
  TruthMapOptions options;
  options.resolution_m = 0.0;
  EXPECT_FALSE(RasterizeTruthMap(scene, options).ok());
  options = {};
  options.hazard_slope_deg = 90.0;
  EXPECT_FALSE(RasterizeTruthMap(scene, options).ok());
  EXPECT_FALSE(RasterizeTruthMap(MakeScene(""), {}).ok());
  EXPECT_FALSE(WriteTruthMap(TruthMap{}, std::filesystem::temp_directory_path()).ok());
}

}  // namespace
}  // namespace flat2d::hal::sim
