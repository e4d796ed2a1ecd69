// flat2dd, the service (issue 10; STYLE.md after chrony): configuration -> map and
// pipeline -> sources and sockets -> threads -> the supervisor loop; torn down in reverse.
//
// Threads (DESIGN.md): LiDAR ingest, CAN ingest (SocketCAN only), localization (matcher +
// graph), API, PPS (when configured), and the calling thread as supervisor. The supervisor waits on a signalfd
// with a 250 ms tick and on each tick: computes the sources' rates, sends STATUS=, sends
// WATCHDOG=1 only if every running thread's heartbeat advanced within watchdog_stall_s,
// persists the pose every persistence.period_s while LOCALIZED, and drives the pose-valid
// line (gpio.pose_valid: on while LOCALIZED). GPIO lines are not reopened on SIGHUP. SIGHUP reloads the
// configuration's map, DBC and option files (sources and sockets keep running; a failed
// reload changes nothing and is reported); SIGTERM or SIGINT stops all threads, persists
// the last good pose and returns.
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "daemon/config/daemon_config.hpp"
#include "daemon/service/api_handler.hpp"
#include "daemon/service/api_server.hpp"
#include "daemon/service/gpio_wiring.hpp"
#include "daemon/service/input_queue.hpp"
#include "daemon/service/localization_worker.hpp"
#include "daemon/service/pose_board.hpp"
#include "daemon/service/sources.hpp"
#include "daemon/service/systemd_notifier.hpp"

namespace flat2d::daemon {

class Daemon {
 public:
  // Everything that can fail at start-up fails here, before READY=1.
  static Result<std::unique_ptr<Daemon>> Start(const std::filesystem::path& config_path);
  ~Daemon();

  // Runs the supervisor until SIGTERM/SIGINT (blocked in every thread by Start). Returns
  // the process's exit code.
  int Run();

 private:
  struct Rates;
  explicit Daemon(std::filesystem::path config_path);

  Status Open(DaemonInputs inputs);
  Status OpenApi(const ApiConfig& api);
  void ApplyStartPose(const DaemonConfig& config);
  void StartThreads();
  void Tick();
  void Reload();
  void PersistPose();
  bool ThreadsProgressing();
  ServiceFigures Figures() const;
  std::string StatusLine() const;

  std::filesystem::path config_path_;
  DaemonConfig config_;
  SystemdNotifier systemd_;
  std::unique_ptr<InputQueue> queue_;
  std::unique_ptr<PoseBoard> board_;
  std::unique_ptr<SourceThread> lidar_;
  std::unique_ptr<SourceThread> can_;
  std::unique_ptr<LocalizationWorker> worker_;
  std::unique_ptr<ApiHandler> handler_;
  std::unique_ptr<ApiServer> server_;
  std::unique_ptr<GpioWiring> gpio_;
  std::vector<std::jthread> threads_;  // joined (stop requested) first in the destructor
  int signal_fd_ = -1;

  std::unique_ptr<Rates> rates_;
  mutable std::mutex error_mutex_;
  std::string last_error_;
  TimeNs started_ns_ = 0;
  TimeNs last_persist_ns_ = 0;
};

}  // namespace flat2d::daemon
