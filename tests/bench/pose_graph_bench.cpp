// Batch pose-graph solve times on the public 2D benchmarks (../shared/data/posegraph),
// from the odometry chain, LM, as in the acceptance tests: SE-Sync's objective (whose
// published optima the tests reach) and the g2o chi2, plus ais2klinik by Gauss-Newton (LM
// stalls on it from the odometry chain). Each
// iteration copies and initializes the graph outside the timed region and optimizes it to
// convergence; counters: linear solves, final cost.
#include <benchmark/benchmark.h>

#include <string>

#include "localization/graph/graph_costs.hpp"
#include "localization/graph/graph_file.hpp"
#include "localization/graph/graph_init.hpp"
#include "localization/graph/graph_optimizer.hpp"
#include "tests/testing/data_path.hpp"

namespace {

using namespace flat2d::localization::graph;

void BM_Optimize(benchmark::State& state, const std::string& file, Initialization init,
                 bool sesync, Solver solver = Solver::kLevenbergMarquardt) {
  const auto path = flat2d::testing::FindData("posegraph/" + file);
  if (!path) return state.SkipWithError(("data not found: " + file).c_str());
  auto read = ReadPoseGraphFile(path->string());
  if (!read.ok()) return state.SkipWithError(read.error().message.c_str());
  if (!Initialize(*read, init).ok()) return state.SkipWithError("initialization failed");
  const PoseGraph start = sesync ? ToSeSyncProblem(*read) : *read;
  OptimizationResult result;
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraph graph = start;
    state.ResumeTiming();
    result = Optimize(graph, {.solver = solver});
    benchmark::DoNotOptimize(result.cost_history.data());
  }
  state.counters["iterations"] = result.iterations;
  state.counters["final_cost"] = result.final_cost();
  state.counters["converged"] = result.converged() ? 1 : 0;
}

BENCHMARK_CAPTURE(BM_Optimize, intel_sesync_odometry, "g2o/intel.g2o", Initialization::kOdometry, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, manhattan_sesync_odometry, "g2o/manhattan.g2o", Initialization::kOdometry, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, city10000_sesync_odometry, "g2o/city10000.g2o", Initialization::kOdometry, true)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Optimize, intel_g2o_odometry, "g2o/intel.g2o", Initialization::kOdometry, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, manhattan_g2o_odometry, "g2o/manhattan.g2o", Initialization::kOdometry, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, city10000_g2o_odometry, "g2o/city10000.g2o", Initialization::kOdometry, false)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Optimize, ais2klinik_sesync_odometry_gn, "g2o/ais2klinik.g2o",
                  Initialization::kOdometry, true, Solver::kGaussNewton)
    ->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
