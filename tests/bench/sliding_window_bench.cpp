// The daemon's sliding-window pose graph on one core (target: a 500-node window solves in
// <= 1 ms, DESIGN.md). A synthetic drive (tests/localization/graph/window_drive.hpp) with
// odometry between consecutive nodes and a scan match on every node, 10 % of them gross
// outliers, fills a full window that has already marginalized nodes. Measured:
//   BM_SolveFromPrediction: a new node predicted from odometry, then Solve to convergence
//     (the daemon's cycle without the add, which is measured apart);
//   BM_OneIteration: one Gauss-Newton iteration (linearize, factorize, solve, re-linearize
//     and factorize for the covariance) of the full window;
//   BM_AddAndMarginalize: AddNode (marginalizing the oldest) + AddOdometry + AddMatch;
//   BM_DaemonCycle: add + marginalize + solve to convergence.
#include <benchmark/benchmark.h>

#include <vector>

#include "localization/graph/sliding_window.hpp"
#include "tests/localization/graph/window_drive.hpp"

namespace {

using namespace flat2d::localization;
using namespace flat2d::localization::graph;

// Enough for the warm-up (capacity + 100) plus the fixed iteration counts below.
constexpr int kDriveNodes = 20'000;

const std::vector<testing::DriveStep>& Drive(const testing::DriveOptions& o) {
  static const std::vector<testing::DriveStep> drive = testing::MakeDrive(o);
  return drive;
}

testing::DriveOptions BenchDrive() {
  testing::DriveOptions o;
  o.nodes = kDriveNodes;
  o.match_every = 1;
  o.outlier_every = 10;
  return o;
}

// A full window of `capacity` nodes that has marginalized 100, solved.
SlidingWindowGraph FullWindow(int capacity, int& next) {
  const testing::DriveOptions o = BenchDrive();
  SlidingWindowOptions options;
  options.capacity = capacity;
  SlidingWindowGraph window = SlidingWindowGraph::Create(options).value();
  for (next = 0; next < capacity + 100; ++next) {
    testing::FeedStep(window, Drive(o), next, o);
    (void)window.Solve(10);
  }
  return window;
}

void BM_SolveFromPrediction(benchmark::State& state) {
  int next = 0;
  SlidingWindowGraph window = FullWindow(static_cast<int>(state.range(0)), next);
  const testing::DriveOptions o = BenchDrive();
  int iterations = 0, solves = 0;
  for (auto _ : state) {
    state.PauseTiming();
    testing::FeedStep(window, Drive(o), next++, o);
    state.ResumeTiming();
    auto solution = window.Solve(10);
    iterations += solution->iterations;
    ++solves;
    benchmark::DoNotOptimize(solution);
  }
  state.counters["iterations"] = static_cast<double>(iterations) / solves;
}

void BM_OneIteration(benchmark::State& state) {
  int next = 0;
  SlidingWindowGraph window = FullWindow(static_cast<int>(state.range(0)), next);
  for (auto _ : state) benchmark::DoNotOptimize(window.Solve(1));
}

void BM_AddAndMarginalize(benchmark::State& state) {
  int next = 0;
  SlidingWindowGraph window = FullWindow(static_cast<int>(state.range(0)), next);
  const testing::DriveOptions o = BenchDrive();
  for (auto _ : state) {
    benchmark::DoNotOptimize(testing::FeedStep(window, Drive(o), next++, o));
  }
}

void BM_DaemonCycle(benchmark::State& state) {
  int next = 0;
  SlidingWindowGraph window = FullWindow(static_cast<int>(state.range(0)), next);
  const testing::DriveOptions o = BenchDrive();
  for (auto _ : state) {
    testing::FeedStep(window, Drive(o), next++, o);
    benchmark::DoNotOptimize(window.Solve(10));
  }
}

// Fixed iteration counts keep every run inside the precomputed drive.
BENCHMARK(BM_SolveFromPrediction)->Arg(100)->Arg(500)->Iterations(3000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OneIteration)->Arg(100)->Arg(500)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AddAndMarginalize)->Arg(500)->Iterations(15000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DaemonCycle)->Arg(500)->Iterations(3000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
