// Pose query latency over flat2dd's Unix socket (issue 10 acceptance: p50/p99 with 1 and
// 50 concurrent clients; target p99 < 200 us with one). A real ApiServer on its own thread
// answers pose_now from a pose board holding 2 s of odometry and a fix; each benchmark
// thread is one client (daemon/client/client.hpp) doing blocking round trips.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "daemon/client/client.hpp"
#include "daemon/service/api_server.hpp"

namespace flat2d::daemon {
namespace {

constexpr TimeNs kStart = 1767225600LL * kNsPerSecond;

struct Server {
  Server() {
    path = (std::filesystem::temp_directory_path() / ("flat2d_bench_" + std::to_string(::getpid()) + ".sock")).string();
    auto created = PoseBoard::Create({.capacity = 512});
    board = std::make_unique<PoseBoard>(std::move(*created));
    for (int k = 0; k <= 200; ++k) {
      localization::OdometrySample sample;
      sample.time_ns = kStart + k * 10 * kNsPerMs;
      sample.local_T_vehicle = localization::Se2(0.01 * k, 0.0, 0.0);
      board->PushOdometry(sample);
    }
    localization::LocalizationFix fix;
    fix.has_fix = true;
    fix.node_ns = kStart + kNsPerSecond;
    fix.node_pose = localization::Se2(1, 2, 0.5);
    fix.state = localization::LocalizerState::kLocalized;
    fix.last_accepted_ns = kStart;
    board->PublishFix(fix);
    handler = std::make_unique<ApiHandler>(*board, MapSummary{}, InitialPoseDefaults{},
                                           [](const InitialPoseRequest&) {}, [] { return ServiceFigures{}; });
    std::vector<hal::net::SocketFd> listeners;
    auto listener = ListenUnix(path, 0660);
    listeners.push_back(std::move(*listener));
    ApiServerOptions options;
    options.max_clients = 128;
    auto created_server = ApiServer::Create(options, std::move(listeners), *handler);
    server = std::move(*created_server);
    thread = std::jthread([this](std::stop_token stop) { server->Run(stop); });
  }
  ~Server() {
    thread.request_stop();
    thread = {};
    std::filesystem::remove(path);
  }
  std::string path;
  std::unique_ptr<PoseBoard> board;
  std::unique_ptr<ApiHandler> handler;
  std::unique_ptr<ApiServer> server;
  std::jthread thread;
};

Server& TheServer() {
  static Server server;
  return server;
}

double Percentile(std::vector<double>& values, double q) {
  const auto rank = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

void BM_PoseNowOverUnixSocket(benchmark::State& state) {
  client::Client client({.endpoint = TheServer().path});
  std::vector<double> latencies_us;
  latencies_us.reserve(1 << 20);
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto pose = client.PoseNow();
    const auto stop = std::chrono::steady_clock::now();
    if (!pose.ok()) state.SkipWithError(pose.error().message.c_str());
    latencies_us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
  }
  if (latencies_us.empty()) return;
  state.counters["p50_us"] = benchmark::Counter(Percentile(latencies_us, 0.5), benchmark::Counter::kAvgThreads);
  state.counters["p99_us"] = benchmark::Counter(Percentile(latencies_us, 0.99), benchmark::Counter::kAvgThreads);
}
BENCHMARK(BM_PoseNowOverUnixSocket)->Threads(1)->Threads(50)->UseRealTime()->MinTime(2.0);

}  // namespace
}  // namespace flat2d::daemon

BENCHMARK_MAIN();
