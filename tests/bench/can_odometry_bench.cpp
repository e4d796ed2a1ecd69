// CAN throughput on one core, on the real comma2k19 RAV4 drive (53,800 frames, 60 s):
// frames decoded per second with a DBC (every signal of the DBC, and only the odometry
// signals), frames parsed from candump text, and odometry updates (mapping + dead
// reckoning + history) per second.
#include <benchmark/benchmark.h>

#include <vector>

#include "hal/can/candump_log.hpp"
#include "hal/can/dbc.hpp"
#include "hal/can/frame_decoder.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "localization/odometry/odometry_config.hpp"
#include "tests/testing/data_path.hpp"

namespace {

using namespace flat2d;

constexpr char kDbc[] = "can/toyota_rav4h_comma2k19/toyota_rav4_hybrid_2017_pt_generated.dbc";
constexpr char kLog[] = "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_bus0.candump.log";

std::vector<hal::can::CanFrame> LoadFrames() {
  std::vector<hal::can::CanFrame> frames;
  const auto path = flat2d::testing::FindData(kLog);
  if (!path) return frames;
  auto reader = hal::can::CandumpReader::Open(*path);
  if (!reader.ok()) return frames;
  hal::can::CanFrame frame;
  while (reader->Next(frame)) frames.push_back(frame);
  return frames;
}

std::optional<hal::can::Dbc> LoadRav4Dbc() {
  const auto path = flat2d::testing::FindData(kDbc);
  if (!path) return std::nullopt;
  auto dbc = hal::can::LoadDbc(*path);
  return dbc.ok() ? std::optional(std::move(dbc).value()) : std::nullopt;
}

void SetRate(benchmark::State& state, std::size_t frames) {
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}

void BM_DecodeAllSignals(benchmark::State& state) {
  const auto frames = LoadFrames();
  const auto dbc = LoadRav4Dbc();
  if (frames.empty() || !dbc) return state.SkipWithError("real data not found");
  auto decoder = hal::can::FrameDecoder::Create(*dbc, hal::can::AllSignals(*dbc));
  if (!decoder.ok()) return state.SkipWithError(decoder.error().message.c_str());
  std::size_t i = 0, done = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(decoder->Decode(frames[i]));
    i = i + 1 == frames.size() ? 0 : i + 1;
    ++done;
  }
  SetRate(state, done);
}

void BM_OdometryUpdates(benchmark::State& state) {
  const auto frames = LoadFrames();
  const auto dbc = LoadRav4Dbc();
  if (frames.empty() || !dbc) return state.SkipWithError("real data not found");
  auto config = localization::LoadOdometryConfig(std::filesystem::path(FLAT2D_SOURCE_DIR) /
                                                 "packaging/config/odometry/toyota_rav4_hybrid_2017.textproto");
  if (!config.ok()) return state.SkipWithError(config.error().message.c_str());
  std::size_t done = 0, updates = 0;
  for (auto _ : state) {
    // One pass over the drive per iteration: times must increase within a pass.
    state.PauseTiming();
    auto odometry = localization::CanOdometry::Create(*dbc, *config);
    state.ResumeTiming();
    for (const auto& frame : frames) updates += odometry->Push(frame).has_value();
    done += frames.size();
  }
  SetRate(state, done);
  state.counters["odometry_updates_per_s"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kIsRate);
}

void BM_ParseCandumpText(benchmark::State& state) {
  const auto path = flat2d::testing::FindData(kLog);
  if (!path) return state.SkipWithError("real data not found");
  std::size_t done = 0;
  for (auto _ : state) {
    auto reader = hal::can::CandumpReader::Open(*path);
    hal::can::CanFrame frame;
    while (reader->Next(frame)) ++done;
  }
  SetRate(state, done);
}

BENCHMARK(BM_DecodeAllSignals);
BENCHMARK(BM_OdometryUpdates)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParseCandumpText)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
