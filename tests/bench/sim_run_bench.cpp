// Simulator speed (issue 5 acceptance): simulated seconds per wall-clock second for an
// HDL-32E at 10 Hz on the campus mapping drive, on one core (the run is single-threaded),
// once into a sink that discards everything (the cost of ray casting, encoding and the
// CAN/truth streams) and once writing the files flat2d-sim writes (lidar.pcap, can.log,
// truth.tum, vehicle.dbc, truth map). Target: at least 5x real time.
//
//   build/release/tests/bench/sim_run_bench --benchmark_counters_tabular=true
// Each iteration simulates kSimulatedSeconds of the drive from its start.
#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <filesystem>

#include "hal/sim/simulation.hpp"
#include "hal/sim/simulation_sinks.hpp"

namespace {

using namespace flat2d::hal::sim;

constexpr double kSimulatedSeconds = 20.0;

class DiscardSink final : public SimulationSink {};

SimulationOptions CampusHdl32e() {
  SimulationOptions options;
  options.world = std::string("campus");
  options.drive = 0;  // the mapping drive
  options.seed = 1;
  options.duration_s = kSimulatedSeconds;
  options.lidar = DefaultLidarOptions(flat2d::hal::velodyne::Model::kHdl32e);
  options.lidar.rotation_hz = 10.0;
  return options;
}

// CPU seconds of this process: on a shared machine wall time also counts other processes,
// so both ratios are reported (on an idle core they agree).
double CpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

void Report(benchmark::State& state, double simulated_s, double wall_s, double cpu_s,
            std::uint64_t packets) {
  state.counters["sim_s_per_wall_s"] = simulated_s / wall_s;
  state.counters["sim_s_per_cpu_s"] = simulated_s / cpu_s;
  state.counters["packets_per_s"] = benchmark::Counter(static_cast<double>(packets), benchmark::Counter::kIsRate);
}

// The world is resolved once: the benchmark measures the run, not building the scene.
void BM_SimulateCampusHdl32eDiscard(benchmark::State& state) {
  SimulationOptions options = CampusHdl32e();
  auto world = ResolveWorld("campus");
  if (!world.ok()) {
    state.SkipWithError(world.error().message.c_str());
    return;
  }
  options.world = *world;
  DiscardSink discard;
  SimulationSink* sinks[] = {&discard};
  double simulated_s = 0.0, wall_s = 0.0;
  std::uint64_t packets = 0;
  const double cpu_start_s = CpuSeconds();
  for (auto _ : state) {
    auto summary = RunSimulation(options, sinks);
    if (!summary.ok()) {
      state.SkipWithError(summary.error().message.c_str());
      return;
    }
    simulated_s += summary->simulated_s;
    wall_s += summary->wall_s;
    packets += summary->data_packets + summary->position_packets;
  }
  Report(state, simulated_s, wall_s, CpuSeconds() - cpu_start_s, packets);
}
BENCHMARK(BM_SimulateCampusHdl32eDiscard)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_SimulateCampusHdl32eFiles(benchmark::State& state) {
  SimulationOptions options = CampusHdl32e();
  auto world = ResolveWorld("campus");
  if (!world.ok()) {
    state.SkipWithError(world.error().message.c_str());
    return;
  }
  options.world = *world;
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("flat2d_sim_bench_" + std::to_string(::getpid()));
  double simulated_s = 0.0, wall_s = 0.0;
  std::uint64_t packets = 0;
  const double cpu_start_s = CpuSeconds();
  for (auto _ : state) {
    auto files = FileSink::Open(directory);
    if (!files.ok()) {
      state.SkipWithError(files.error().message.c_str());
      return;
    }
    SimulationSink* sinks[] = {&*files};
    auto summary = RunSimulation(options, sinks);
    if (!summary.ok()) {
      state.SkipWithError(summary.error().message.c_str());
      return;
    }
    simulated_s += summary->simulated_s;
    wall_s += summary->wall_s;
    packets += summary->data_packets + summary->position_packets;
  }
  std::filesystem::remove_all(directory);
  Report(state, simulated_s, wall_s, CpuSeconds() - cpu_start_s, packets);
}
BENCHMARK(BM_SimulateCampusHdl32eFiles)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
