// Line and plane extraction (thesis 8.1) per HDL-32E revolution on one core (issue 13;
// target p50 <= 10 ms, thesis Fig. 8.7: > 20 Hz on an i7-3630QM), with and without the
// non-vertical removal (Arg 1 / 0): a real revolution (the fast_gicp pair's first sweep)
// and a simulated one in the office corridor where most points are on walls. The cloud is
// built outside the timed loop; the extractor is warm (a vehicle runs it every revolution).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "hal/cloud/pcd_file.hpp"
#include "hal/sim/lidar_options.hpp"
#include "hal/sim/scene.hpp"
#include "hal/sim/worlds.hpp"
#include "maps/features3d/feature_extractor.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/range3d/range_frame.hpp"
#include "tests/testing/data_path.hpp"

namespace {

using namespace flat2d;
using maps::features3d::FeatureExtractionOptions;
using maps::features3d::FeatureExtractor;

constexpr int kColumns = 2160;  // the shipped config's azimuth columns
constexpr double kRotationRpm = 600.0;  // ... and its rotation speed
constexpr double kSensorHeightM = 1.9;

std::optional<FeatureExtractionOptions> Shipped(bool removal) {
  auto options = maps::features3d::LoadFeatureOptions(std::filesystem::path(FLAT2D_SOURCE_DIR) /
                                                      "packaging/config/features3d/features3d.textproto");
  if (!options.ok()) return std::nullopt;
  options->mutable_vertical()->set_enabled(removal);
  return *options;
}

// One ray per pixel of the HDL-32E image from the office mapping drive's start, 1.9 m up,
// looking along the corridor; range noise as the simulator's HDL-32E (sigma 1 cm, seeded).
std::vector<Eigen::Vector3f> OfficeRevolution(const maps::range3d::RangeProjection& projection) {
  auto description = hal::sim::BuiltInWorld("office");
  auto scene = hal::sim::Scene::Create(*description);
  const auto& waypoints = description->drives(0).waypoints();
  const Eigen::Vector2d start(waypoints[0].x(), waypoints[0].y()), next(waypoints[1].x(), waypoints[1].y());
  const Eigen::Vector2d heading = (next - start).normalized();
  const Eigen::Vector3d origin(start.x(), start.y(), kSensorHeightM);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, hal::sim::LidarOptions{}.range_noise_sigma_m);
  std::vector<Eigen::Vector3f> points;
  for (int row = 0; row < projection.rows(); ++row) {
    for (int col = 0; col < projection.cols(); ++col) {
      const Eigen::Vector3d d = projection.Unproject(row, col, 1.0F).cast<double>().normalized();
      const Eigen::Vector3d world(heading.x() * d.x() - heading.y() * d.y(), heading.y() * d.x() + heading.x() * d.y(),
                                  d.z());
      const auto hit = scene->Cast(origin, world, 100.0, 0.0);
      if (hit) points.push_back(((hit->range_m + noise(rng)) * d).cast<float>());
    }
  }
  return points;
}

void Run(benchmark::State& state, const std::vector<Eigen::Vector3f>& points, maps::range3d::SensorModel sensor,
         const maps::range3d::RangeProjection& projection) {
  const auto options = Shipped(state.range(0) != 0);
  if (!options) {
    state.SkipWithError("shipped features3d.textproto not readable");
    return;
  }
  FeatureExtractor extractor(projection, maps::features3d::OptionsForSensor(*options, sensor));
  extractor.Extract(points, Eigen::Vector3f::UnitZ());  // warm: buffers sized
  maps::features3d::ExtractionStats sum;
  for (auto _ : state) {
    const auto& features = extractor.Extract(points, Eigen::Vector3f::UnitZ());
    benchmark::DoNotOptimize(features.planes.data());
    const auto& s = extractor.stats();
    sum.image_ms += s.image_ms, sum.vertical_ms += s.vertical_ms, sum.normals_ms += s.normals_ms;
    sum.segmentation_ms += s.segmentation_ms, sum.fitting_ms += s.fitting_ms;
  }
  const double n = static_cast<double>(state.iterations());
  const auto& s = extractor.stats();
  state.counters["points_left"] = static_cast<double>(s.vertical_points);
  state.counters["planes"] = static_cast<double>(extractor.Extract(points, Eigen::Vector3f::UnitZ()).planes.size());
  state.counters["image_ms"] = sum.image_ms / n;
  state.counters["removal_ms"] = sum.vertical_ms / n;
  state.counters["normals_ms"] = sum.normals_ms / n;
  state.counters["segment_ms"] = sum.segmentation_ms / n;
  state.counters["fit_ms"] = sum.fitting_ms / n;
}

void BM_FeaturesRealHdl32(benchmark::State& state) {
  const auto path = flat2d::testing::FindData("lidar3d/hdl32e_fast_gicp_pair/251370668.pcd");
  if (!path) {
    state.SkipWithError("real data not found: lidar3d/hdl32e_fast_gicp_pair (set FLAT2D_DATA)");
    return;
  }
  const auto cloud = hal::cloud::ReadPcd(*path);
  if (!cloud.ok()) {
    state.SkipWithError("unreadable PCD");
    return;
  }
  const auto sensor = maps::range3d::DetectLidar(cloud->points);
  Run(state, cloud->points, sensor, maps::range3d::LidarProjection(sensor, kColumns, kRotationRpm));
}
BENCHMARK(BM_FeaturesRealHdl32)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_FeaturesSimOfficeHdl32(benchmark::State& state) {
  const auto projection = maps::range3d::LidarProjection(maps::range3d::SensorModel::kHdl32e, kColumns, kRotationRpm);
  Run(state, OfficeRevolution(projection), maps::range3d::SensorModel::kHdl32e, projection);
}
BENCHMARK(BM_FeaturesSimOfficeHdl32)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
