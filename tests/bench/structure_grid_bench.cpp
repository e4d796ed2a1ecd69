// Structure grids on one core (issue 6): the per-packet work of the daemon's grid thread
// (decode, motion compensation from the pose history, slope classes or voxel popcount,
// marking, fill-in, free space) as a multiple of the HDL-32E line rate (target >= 20x), and
// the latency from a revolution's last packet to its published grid (target p99 < 1 ms).
//
// Input: 20 s of the simulator's campus mapping drive (HDL-32E, 10 Hz), simulated once and
// kept in memory; poses are the drive's truth at 200 Hz, as the odometry history would
// give them. Each revolution is gridded in a 50 x 50 m grid at 5 cm (the shipped config).
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "hal/sim/lidar_simulator.hpp"
#include "hal/sim/simulation.hpp"
#include "hal/velodyne/packet_decoder.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/revolution_gridder.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace {

using namespace flat2d;

constexpr double kLineRatePacketsPerS = 1808.0;  // HDL-32E, single return
constexpr double kSeconds = 20.0;

struct Drive {
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<TimeNs> device_times;
  std::vector<maps::StampedPose2d> poses;
  hal::velodyne::LaserTable table;
};

const Drive& CampusDrive() {
  static const Drive drive = [] {
    Drive d;
    auto world = hal::sim::ResolveWorld("campus");
    auto scene = hal::sim::Scene::Create(*world);
    auto trajectory = hal::sim::Trajectory::Create(*scene, world->drives(0));
    hal::sim::LidarOptions options = hal::sim::DefaultLidarOptions(hal::velodyne::Model::kHdl32e);
    options.position_packets = false;
    auto simulator = hal::sim::LidarSimulator::Create(*scene, *trajectory, options, 1);
    d.table = simulator->laser_table();
    while (true) {
      const hal::sim::SimulatedPacket& packet = simulator->NextDataPacket();
      if (packet.drive_time_s > kSeconds) break;
      d.payloads.emplace_back(packet.payload.begin(), packet.payload.end());
      d.device_times.push_back(packet.device_time_ns);
    }
    for (double t = 0.0; t <= kSeconds + 1.0; t += 0.005) {
      const hal::sim::VehicleState state = trajectory->At(t);
      d.poses.push_back(maps::Flatten(simulator->UnixTimeNs(t), state.world_T_vehicle));
    }
    return d;
  }();
  return drive;
}

maps::StructureGridOptions ShippedOptions(maps::StructureGridOptions::Method method) {
  auto options = maps::LoadStructureGridOptions(std::filesystem::path(FLAT2D_SOURCE_DIR) /
                                                "packaging/config/grid/structure_grid.textproto");
  maps::StructureGridOptions grid = options.ok() ? *options : maps::StructureGridOptions();
  grid.set_method(method);
  return grid;
}

// Heap bytes in use (glibc): small blocks plus mmapped large ones.
double HeapBytes() {
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd);
}

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(p * static_cast<double>(values.size() - 1))];
}

void BM_GridPerPacket(benchmark::State& state, maps::StructureGridOptions::Method method,
                      double free_space_range_m) {
  const Drive& drive = CampusDrive();
  const maps::InterpolatedPoses poses(drive.poses);
  maps::StructureGridOptions options = ShippedOptions(method);
  if (free_space_range_m > 0.0) options.set_free_space_range_m(free_space_range_m);
  const double heap_before = HeapBytes();
  auto gridder = maps::RevolutionGridder::Create(drive.table, options, &poses);
  // Everything the gridder holds (both buffers), sized once at Create.
  state.counters["gridder_MB"] = (HeapBytes() - heap_before) / 1e6;
  if (!gridder.ok()) {
    state.SkipWithError(gridder.error().message.c_str());
    return;
  }
  hal::velodyne::PacketDecoder decoder(drive.table);
  auto decoded = std::make_unique<hal::velodyne::DecodedPacket>();
  // Latency of the Add that completes a revolution: the work after its last packet.
  std::vector<double> latencies_ms;
  latencies_ms.reserve(1 << 16);
  std::size_t packets = 0, index = 0;
  for (auto _ : state) {
    decoder.Decode(drive.payloads[index], *decoded);
    for (int f = 0; f < decoded->num_fans; ++f) decoded->fans[static_cast<std::size_t>(f)].stamp_ns += drive.device_times[index];
    const auto start = std::chrono::steady_clock::now();
    const maps::PublishedGrid* published =
        gridder->Add(std::span(decoded->fans).first(static_cast<std::size_t>(decoded->num_fans)));
    if (published != nullptr && latencies_ms.size() < latencies_ms.capacity()) {
      latencies_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    benchmark::DoNotOptimize(published);
    ++packets;
    // Wrapping round to the first packet restarts time: a new stream, as after a restart.
    if (++index == drive.payloads.size()) index = 0;
  }
  state.counters["x_line_rate"] = benchmark::Counter(static_cast<double>(packets) / kLineRatePacketsPerS,
                                                     benchmark::Counter::kIsRate);
  state.counters["publish_p50_ms"] = Percentile(latencies_ms, 0.5);
  state.counters["publish_p99_ms"] = Percentile(latencies_ms, 0.99);
  state.counters["publish_max_ms"] = Percentile(latencies_ms, 1.0);
  state.counters["revolutions"] = static_cast<double>(latencies_ms.size());
}

// The shipped configuration (free space to 30 m), and the slope method with free space cast
// only 1 cm: how much of the per-packet time the free-space rays take.
BENCHMARK_CAPTURE(BM_GridPerPacket, slope, maps::StructureGridOptions::METHOD_SLOPE, 0.0)->MinTime(3.0);
BENCHMARK_CAPTURE(BM_GridPerPacket, slope_free_space_1cm, maps::StructureGridOptions::METHOD_SLOPE, 0.01)
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_GridPerPacket, cartesian_popcount, maps::StructureGridOptions::METHOD_CARTESIAN_POPCOUNT, 0.0)
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_GridPerPacket, polar_popcount, maps::StructureGridOptions::METHOD_POLAR_POPCOUNT, 0.0)
    ->MinTime(3.0);

// The decoder alone over the same packets, to split the per-packet time.
void BM_DecodeOnly(benchmark::State& state) {
  const Drive& drive = CampusDrive();
  hal::velodyne::PacketDecoder decoder(drive.table);
  auto decoded = std::make_unique<hal::velodyne::DecodedPacket>();
  std::size_t packets = 0, index = 0;
  for (auto _ : state) {
    decoder.Decode(drive.payloads[index], *decoded);
    benchmark::DoNotOptimize(decoded->num_fans);
    ++packets;
    if (++index == drive.payloads.size()) index = 0;
  }
  state.counters["x_line_rate"] = benchmark::Counter(static_cast<double>(packets) / kLineRatePacketsPerS,
                                                     benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DecodeOnly)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
