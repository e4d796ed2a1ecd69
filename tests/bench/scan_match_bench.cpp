// Correlative scan matching speed (issue 7): tracking (+-1.5 m, +-6 deg) and global (20 m,
// all headings) matches of a Velodyne-like structure scan against a 100 x 100 m synthetic
// outdoor map at 5 cm. Each benchmark times many single matches itself and reports the
// median and 99th percentile (p50_ms, p99_ms) of the thread's CPU time per match (the build
// machine is shared, so wall time would measure the neighbours), plus the wall-clock median
// (wall_p50_ms) and the fraction that recovered the true pose within 5 cm and 0.5 deg.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "localization/matching/correlative_matcher.hpp"
#include "localization/matching/scan_points.hpp"
#include "tests/localization/matching/synthetic_world.hpp"

namespace flat2d::localization {
namespace {

constexpr double kResolution = 0.05;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr std::size_t kMaxPoints = 1500;

struct Scene {
  testing::World world = testing::OutdoorWorld(100.0, 1);
  MatchGrid map = testing::Rasterize(world, kResolution, 2.0);
};

const Scene& TheScene() {
  static const Scene scene;
  return scene;
}

// A structure scan as the daemon's grid would give it: 3600 rays (0.1 deg, as an
// HDL-32E's structure cells), 60 m reach, 2 cm noise, decimated to one point per 10 cm.
struct Sample {
  Se2 truth;
  std::vector<Eigen::Vector2d> points;
  std::size_t raw_points = 0;
};

std::vector<Sample> Samples(int count, std::uint32_t seed) {
  std::mt19937 random(seed);
  testing::LaserModel laser;
  laser.beams = 3600;
  laser.max_range = 60.0;
  laser.noise_sigma = 0.02;
  ScanPoints scan(4000);
  std::vector<Sample> samples;
  while (static_cast<int>(samples.size()) < count) {
    const Se2 truth = testing::RandomFreePose(TheScene().world, 1.0, random);
    const std::vector<Eigen::Vector2d> raw = testing::CastScan(TheScene().world, truth, laser, &random);
    if (raw.size() < 2000) continue;  // inside a building or facing open field: not typical
    scan.Clear();
    for (const Eigen::Vector2d& p : raw) scan.Add(p);
    scan.VoxelDecimate(0.1);
    if (scan.size() > kMaxPoints) continue;
    samples.push_back({truth, {scan.points().begin(), scan.points().end()}, raw.size()});
  }
  return samples;
}

double ThreadCpuMilliseconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

double Percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
}

void RunMatches(benchmark::State& state, const MatcherLimits& limits, const SearchWindow& window,
                double offset_linear, double offset_angular, int count, bool relocalize = false,
                const RelocalizationOptions& relocalization = {}) {
  CorrelativeMatcher matcher(limits, MatcherOptions{});
  if (!matcher.SetMap(TheScene().map).ok()) {
    state.SkipWithError("map exceeds the limits");
    return;
  }
  const std::vector<Sample> samples = Samples(count, 11);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> offset(-offset_linear, offset_linear);
  std::uniform_real_distribution<double> turn(-offset_angular, offset_angular);
  std::vector<double> milliseconds;
  std::vector<double> wall_milliseconds;
  double points = 0.0;
  double raw_points = 0.0;
  double candidates = 0.0;
  int recovered = 0;
  for (auto _ : state) {
    for (const Sample& sample : samples) {
      // Braces: the draws are made in order (a call's arguments have none).
      const Se2 prediction{sample.truth.x() + offset(random), sample.truth.y() + offset(random),
                           sample.truth.theta() + turn(random)};
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = ThreadCpuMilliseconds();
      const MatchResult result = relocalize ? matcher.Relocalize(sample.points, prediction, window, relocalization)
                                            : matcher.Match(sample.points, prediction, window);
      milliseconds.push_back(ThreadCpuMilliseconds() - cpu_start);
      const auto stop = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(result);
      wall_milliseconds.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
      points += static_cast<double>(sample.points.size());
      raw_points += static_cast<double>(sample.raw_points);
      candidates += static_cast<double>(result.evaluated_candidates);
      const double dt = (result.map_T_vehicle.translation() - sample.truth.translation()).norm();
      const double dr = std::abs(NormalizeAngle(result.map_T_vehicle.theta() - sample.truth.theta()));
      if (result.ok() && dt <= kResolution && dr <= 0.5 * kDeg) ++recovered;
    }
  }
  const double matches = static_cast<double>(milliseconds.size());
  state.counters["p50_ms"] = Percentile(milliseconds, 0.5);
  state.counters["p99_ms"] = Percentile(milliseconds, 0.99);
  state.counters["max_ms"] = Percentile(milliseconds, 1.0);
  state.counters["wall_p50_ms"] = Percentile(wall_milliseconds, 0.5);
  state.counters["points"] = points / matches;
  state.counters["raw_points"] = raw_points / matches;
  state.counters["candidates"] = candidates / matches;
  state.counters["recovered"] = recovered / matches;
}

void BM_TrackingMatch(benchmark::State& state) {
  const MatcherLimits limits{kMaxPoints, 2100 * 2100, 30, 512, 7};
  RunMatches(state, limits, SearchWindow{1.5, 6.0 * kDeg}, 0.5, 3.0 * kDeg, 300);
}
BENCHMARK(BM_TrackingMatch)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_GlobalMatch(benchmark::State& state) {
  const MatcherLimits limits{kMaxPoints, 2100 * 2100, 400, 8192, 11};
  RunMatches(state, limits, SearchWindow{20.0, std::numbers::pi}, 15.0, std::numbers::pi, 10);
}
BENCHMARK(BM_GlobalMatch)->Iterations(1)->Unit(benchmark::kMillisecond);

// The daemon's relocalization: Relocalize's two stages over the same window.
void BM_Relocalize(benchmark::State& state) {
  const MatcherLimits limits{kMaxPoints, 2100 * 2100, 400, 8192, 11};
  RelocalizationOptions relocalization;
  relocalization.decimation_m = static_cast<double>(state.range(0)) / 100.0;
  relocalization.step_range_cap_m = static_cast<double>(state.range(1));
  RunMatches(state, limits, SearchWindow{20.0, std::numbers::pi}, 15.0, std::numbers::pi, 20, /*relocalize=*/true,
             relocalization);
}
BENCHMARK(BM_Relocalize)->Args({50, 3})->Args({80, 3})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace flat2d::localization

BENCHMARK_MAIN();
