// Batch pose-graph solve times on the public 2D benchmarks (../shared/data/posegraph),
// from the odometry chain, LM, as in the acceptance tests: SE-Sync's objective (whose
// published optima the tests reach) and the g2o chi2, plus ais2klinik by Gauss-Newton (LM
// stalls on it from the odometry chain). Each
// iteration copies and initializes the graph outside the timed region and optimizes it to
// convergence; counters: linear solves, final cost. The SE(3) benchmarks (sphere, torus,
// garage, cubicle) minimize SE-Sync's f from the start the reference test uses, and the
// chordal initialization is timed on its own.
#include <benchmark/benchmark.h>

#include <string>

#include "localization/graph/graph_costs.hpp"
#include "localization/graph/graph_file.hpp"
#include "localization/graph/graph_init.hpp"
#include "localization/graph/graph_optimizer.hpp"
#include "localization/graph/g2o_se3_io.hpp"
#include "localization/graph/se3_costs.hpp"
#include "localization/graph/se3_graph_optimizer.hpp"
#include "localization/graph/se3_init.hpp"
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

void BM_OptimizeSe3(benchmark::State& state, const std::string& file, Initialization init) {
  const auto path = flat2d::testing::FindData("posegraph/" + file);
  if (!path) return state.SkipWithError(("data not found: " + file).c_str());
  auto read = ReadG2oSe3File(path->string());
  if (!read.ok()) return state.SkipWithError(read.error().message.c_str());
  if (!Initialize(*read, init).ok()) return state.SkipWithError("initialization failed");
  const Se3PoseGraph start = ToSeSyncProblem(*read);
  OptimizationResult result;
  for (auto _ : state) {
    state.PauseTiming();
    Se3PoseGraph graph = start;
    state.ResumeTiming();
    result = Optimize(graph);
    benchmark::DoNotOptimize(result.cost_history.data());
  }
  state.counters["iterations"] = result.iterations;
  state.counters["final_cost"] = result.final_cost();
  state.counters["converged"] = result.converged() ? 1 : 0;
}

void BM_ChordalSe3(benchmark::State& state, const std::string& file) {
  const auto path = flat2d::testing::FindData("posegraph/" + file);
  if (!path) return state.SkipWithError(("data not found: " + file).c_str());
  auto read = ReadG2oSe3File(path->string());
  if (!read.ok()) return state.SkipWithError(read.error().message.c_str());
  for (auto _ : state) {
    state.PauseTiming();
    Se3PoseGraph graph = *read;
    state.ResumeTiming();
    if (!InitializeChordal(graph).ok()) return state.SkipWithError("initialization failed");
    benchmark::DoNotOptimize(graph.nodes.data());
  }
}

BENCHMARK_CAPTURE(BM_OptimizeSe3, sphere2500_sesync_file, "g2o/sphere2500.g2o", Initialization::kFile)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_OptimizeSe3, torus3D_sesync_chordal, "g2o/torus3D.g2o", Initialization::kChordal)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_OptimizeSe3, garage_sesync_file, "g2o/parking-garage.g2o", Initialization::kFile)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_OptimizeSe3, cubicle_sesync_file, "g2o/cubicle.g2o", Initialization::kFile)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_OptimizeSe3, cubicle_sesync_chordal, "g2o/cubicle.g2o", Initialization::kChordal)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ChordalSe3, torus3D, "g2o/torus3D.g2o")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ChordalSe3, cubicle, "g2o/cubicle.g2o")->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
