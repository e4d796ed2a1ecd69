#include "daemon/service/daemon.hpp"

#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cinttypes>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>

#include "daemon/service/pose_store.hpp"
#include "hal/can/candump_log.hpp"
#include "hal/common/time.hpp"
#include "hal/net/ipv4.hpp"

namespace flat2d::daemon {
namespace {

constexpr int kTickMs = 250;

TimeNs ClockNs(clockid_t clock) {
  timespec now{};
  clock_gettime(clock, &now);
  return static_cast<TimeNs>(now.tv_sec) * kNsPerSecond + now.tv_nsec;
}
TimeNs MonotonicNs() { return ClockNs(CLOCK_MONOTONIC); }

std::uint64_t ResidentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  std::uint64_t resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

void Log(const std::string& line) { std::fprintf(stderr, "flat2dd: %s\n", line.c_str()); }

Eigen::Matrix3d Covariance(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d(sigma_m * sigma_m, sigma_m * sigma_m, sigma_rad * sigma_rad).asDiagonal();
}

Result<std::unique_ptr<localization::LocalizationPipeline>> MakePipeline(DaemonInputs& inputs) {
  localization::LocalizationPipelineOptions options;
  options.stream = StreamOptionsFor(inputs.config.lidar());
  options.grid = inputs.grid;
  options.localizer = inputs.localizer;
  return localization::LocalizationPipeline::Create(inputs.dbc, inputs.odometry, std::move(*inputs.map), options);
}

}  // namespace

// Sources' rates over the last tick interval, and the threads' progress.
struct Daemon::Rates {
  struct Watched {
    std::string name;
    std::function<std::uint64_t()> heartbeat;
    std::function<bool()> finished;
    std::uint64_t last = 0;
    TimeNs changed_ns = 0;
  };
  std::vector<Watched> watched;
  std::atomic<double> lidar_hz{0.0};
  std::atomic<double> can_hz{0.0};
  std::uint64_t last_datagrams = 0;
  std::uint64_t last_frames = 0;
  TimeNs last_ns = 0;
};

Daemon::Daemon(std::filesystem::path config_path)
    : config_path_(std::move(config_path)), rates_(std::make_unique<Rates>()), started_ns_(MonotonicNs()) {}

Daemon::~Daemon() {
  for (std::jthread& thread : threads_) thread.request_stop();
  if (server_) server_->Stop();
  threads_.clear();  // joins
  if (signal_fd_ >= 0) ::close(signal_fd_);
}

Result<std::unique_ptr<Daemon>> Daemon::Start(const std::filesystem::path& config_path) {
  // Blocked before any thread starts, so every thread inherits the mask and only the
  // supervisor's signalfd sees them.
  sigset_t signals;
  sigemptyset(&signals);
  for (int signal : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&signals, signal);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::unique_ptr<Daemon> daemon(new Daemon(config_path));
  daemon->signal_fd_ = signalfd(-1, &signals, SFD_CLOEXEC | SFD_NONBLOCK);
  if (daemon->signal_fd_ < 0) return MakeError("signalfd failed");
  auto inputs = LoadDaemonInputs(config_path);
  if (!inputs.ok()) return inputs.error();
  if (Status opened = daemon->Open(std::move(*inputs)); !opened.ok()) return opened.error();
  daemon->StartThreads();
  daemon->systemd_.Ready();
  Log("ready: map " + daemon->config_.map() + ", api " + daemon->config_.api().unix_socket());
  return daemon;
}

Status Daemon::Open(DaemonInputs inputs) {
  config_ = inputs.config;
  const MapSummary map = SummarizeMap(*inputs.map, config_.map());
  auto pipeline = MakePipeline(inputs);
  if (!pipeline.ok()) return pipeline.error();
  auto board = PoseBoard::Create(localization::PoseHistoryOptions{});
  if (!board.ok()) return board.error();
  board_ = std::make_unique<PoseBoard>(std::move(*board));
  queue_ = std::make_unique<InputQueue>(config_.lidar().ring_datagrams(), config_.can().ring_frames());
  auto lidar = OpenLidarSource(config_.lidar());
  if (!lidar.ok()) return lidar.error();
  lidar_ = std::move(*lidar);
  auto can = OpenCanSource(config_.can());
  if (!can.ok()) return can.error();
  can_ = std::move(*can);
  auto gpio = GpioWiring::Open(config_.gpio());
  if (!gpio.ok()) return gpio.error();
  gpio_ = std::move(*gpio);
  std::optional<CanLogFollower> follower;
  if (config_.can().has_candump()) {
    auto log = hal::can::CandumpReader::Open(config_.can().candump().path());
    if (!log.ok()) return log.error();
    follower.emplace(std::move(*log), /*run_through_silence=*/config_.lidar().has_udp());
  }
  worker_ = std::make_unique<LocalizationWorker>(*queue_, *board_, std::move(*pipeline), std::move(follower));
  const InitialPoseDefaults defaults = config_.has_initial_pose()
                                           ? InitialPoseDefaults{config_.initial_pose().sigma_m(),
                                                                 config_.initial_pose().sigma_rad()}
                                           : InitialPoseDefaults{};
  handler_ = std::make_unique<ApiHandler>(
      *board_, map, defaults, [this](const InitialPoseRequest& request) { worker_->RequestInitialPose(request); },
      [this] { return Figures(); });
  if (Status api = OpenApi(config_.api()); !api.ok()) return api;
  ApplyStartPose(config_);
  return Status::Ok();
}

Status Daemon::OpenApi(const ApiConfig& api) {
  std::vector<hal::net::SocketFd> listeners = ActivatedSockets();
  if (listeners.empty()) {
    auto unix_socket = ListenUnix(api.unix_socket(), api.unix_mode());
    if (!unix_socket.ok()) return unix_socket.error();
    listeners.push_back(std::move(*unix_socket));
  }
  if (!api.tcp_address().empty()) {
    auto tcp = ListenTcp(*hal::net::ParseIpv4(api.tcp_address()), static_cast<std::uint16_t>(api.tcp_port()));
    if (!tcp.ok()) return tcp.error();
    listeners.push_back(std::move(*tcp));
  }
  ApiServerOptions options{.max_clients = api.max_clients(),
                           .max_message_bytes = api.max_message_bytes(),
                           .max_subscribe_hz = api.max_subscribe_hz()};
  auto server = ApiServer::Create(options, std::move(listeners), *handler_);
  if (!server.ok()) return server.error();
  server_ = std::move(*server);
  return Status::Ok();
}

// A persisted pose (warm start, wide: the vehicle may have moved while we were down), else
// the configured one, else none (a client must set it).
void Daemon::ApplyStartPose(const DaemonConfig& config) {
  const Persistence& persistence = config.persistence();
  if (!persistence.l2g_path().empty()) {
    auto persisted = LoadPersistedPose(persistence.l2g_path());
    if (persisted.ok() && persisted->map() == config.map()) {
      Log("warm start from " + persistence.l2g_path());
      // At its own time: if the odometry still covers it (a replay), odometry carries it on.
      worker_->RequestInitialPose({persisted->time_ns(),
                                   localization::Se2(Eigen::Vector2d(persisted->x(), persisted->y()), persisted->theta()),
                                   Covariance(persistence.warm_start_sigma_m(), persistence.warm_start_sigma_rad())});
      return;
    }
    if (!persisted.ok() && std::filesystem::exists(persistence.l2g_path())) Log("ignored: " + persisted.error().message);
  }
  if (config.has_initial_pose()) {
    const InitialPose& initial = config.initial_pose();
    worker_->RequestInitialPose({0, localization::Se2(Eigen::Vector2d(initial.x(), initial.y()), initial.theta()),
                                 Covariance(initial.sigma_m(), initial.sigma_rad())});
  }
}

void Daemon::StartThreads() {
  const TimeNs now_ns = MonotonicNs();
  // Each thread carries a name for top -H and /proc/PID/task/*/comm (15 characters at most)
  // and is watched under its own: WATCHDOG=1 only while every one makes progress.
  auto spawn = [&](const char* thread_name, std::string watched_name, std::function<void(std::stop_token)> body,
                   std::function<std::uint64_t()> heartbeat, std::function<bool()> finished) {
    std::jthread& thread = threads_.emplace_back(std::move(body));
    ::pthread_setname_np(thread.native_handle(), thread_name);
    rates_->watched.push_back({std::move(watched_name), std::move(heartbeat), std::move(finished), 0, now_ns});
  };
  const auto never = [] { return false; };
  spawn("f2d-lidar", "lidar", [this](std::stop_token stop) { lidar_->Run(stop, *queue_); },
        [this] { return lidar_->heartbeat(); }, [this] { return lidar_->finished(); });
  if (can_) {
    spawn("f2d-can", "can", [this](std::stop_token stop) { can_->Run(stop, *queue_); },
          [this] { return can_->heartbeat(); }, [this] { return can_->finished(); });
  }
  spawn("f2d-localize", "localization", [this](std::stop_token stop) { worker_->Run(stop); },
        [this] { return worker_->heartbeat(); }, never);
  spawn("f2d-api", "api", [this](std::stop_token stop) { server_->Run(stop); }, [this] { return server_->heartbeat(); },
        never);
  if (gpio_->has_pps()) {
    spawn("f2d-pps", "pps", [this](std::stop_token stop) { gpio_->RunPps(stop); },
          [this] { return gpio_->pps_heartbeat(); }, never);
  }
  rates_->last_ns = now_ns;
}

int Daemon::Run() {
  const std::optional<TimeNs> watchdog = systemd_.WatchdogInterval();
  pollfd wait{signal_fd_, POLLIN, 0};
  while (true) {
    const int ready = ::poll(&wait, 1, kTickMs);
    if (ready > 0) {
      signalfd_siginfo info{};
      if (::read(signal_fd_, &info, sizeof(info)) == static_cast<ssize_t>(sizeof(info))) {
        if (info.ssi_signo == SIGHUP) {
          Reload();
        } else {
          break;
        }
      }
    }
    Tick();
    if (watchdog && ThreadsProgressing()) systemd_.WatchdogPing();
  }
  systemd_.Stopping();
  Log("stopping");
  gpio_->Stop();  // the pose-valid line goes off before the pose stops being served
  for (std::jthread& thread : threads_) thread.request_stop();
  server_->Stop();
  threads_.clear();
  PersistPose();
  return 0;
}

void Daemon::Tick() {
  const TimeNs now_ns = MonotonicNs();
  const localization::LocalizationFix fix = board_->fix();
  gpio_->UpdatePoseValid(fix.has_fix && fix.state == localization::LocalizerState::kLocalized, now_ns);
  const InputQueueStats& stats = queue_->stats();
  const std::uint64_t datagrams = stats.datagrams.load();
  const std::uint64_t frames = board_->health().can_frames;
  const double elapsed_s = static_cast<double>(now_ns - rates_->last_ns) * kSecondsPerNs;
  if (elapsed_s >= 1.0) {
    rates_->lidar_hz = static_cast<double>(datagrams - rates_->last_datagrams) / elapsed_s;
    rates_->can_hz = static_cast<double>(frames - rates_->last_frames) / elapsed_s;
    rates_->last_datagrams = datagrams;
    rates_->last_frames = frames;
    rates_->last_ns = now_ns;
    systemd_.Status(StatusLine());
  }
  if (static_cast<double>(now_ns - last_persist_ns_) * kSecondsPerNs >= config_.persistence().period_s()) {
    last_persist_ns_ = now_ns;
    PersistPose();
  }
}

bool Daemon::ThreadsProgressing() {
  const TimeNs now_ns = MonotonicNs();
  const auto stall_ns = static_cast<TimeNs>(config_.watchdog_stall_s() * 1e9);
  bool progressing = true;
  for (Rates::Watched& thread : rates_->watched) {
    const std::uint64_t beat = thread.heartbeat();
    if (beat != thread.last || thread.finished()) {
      thread.last = beat;
      thread.changed_ns = now_ns;
    } else if (now_ns - thread.changed_ns > stall_ns) {
      progressing = false;
    }
  }
  return progressing;
}

void Daemon::Reload() {
  systemd_.Reloading();
  Log("reloading " + config_path_.string());
  auto inputs = LoadDaemonInputs(config_path_);
  if (inputs.ok()) {
    const MapSummary map = SummarizeMap(*inputs->map, inputs->config.map());
    auto pipeline = MakePipeline(*inputs);
    if (pipeline.ok()) {
      worker_->ReplacePipeline(std::move(*pipeline));
      handler_->set_map(map);
      config_.set_map(inputs->config.map());
      Log("reloaded");
    } else {
      inputs = pipeline.error();
    }
  }
  if (!inputs.ok()) {
    Log("reload failed, running on: " + inputs.error().message);
    const std::lock_guard lock(error_mutex_);
    last_error_ = "reload: " + inputs.error().message;
  }
  systemd_.Ready();
}

void Daemon::PersistPose() {
  const std::string& path = config_.persistence().l2g_path();
  if (path.empty()) return;
  const ServedPose served = board_->ServeNow();  // the pose and the L2G it was composed with
  const localization::GlobalPose& pose = served.pose;
  const localization::LocalizationFix& fix = served.fix;
  if (!pose.ok || pose.state != localization::LocalizerState::kLocalized) return;
  PersistedPose persisted;
  persisted.set_time_ns(pose.time_ns);
  persisted.set_x(pose.global_T_vehicle.translation().x());
  persisted.set_y(pose.global_T_vehicle.translation().y());
  persisted.set_theta(pose.global_T_vehicle.theta());
  persisted.set_l2g_x(fix.global_T_local.translation().x());
  persisted.set_l2g_y(fix.global_T_local.translation().y());
  persisted.set_l2g_theta(fix.global_T_local.theta());
  persisted.set_map(config_.map());
  if (Status saved = SavePersistedPose(path, persisted); !saved.ok()) {
    const std::lock_guard lock(error_mutex_);
    if (last_error_ != saved.error().message) Log(saved.error().message);
    last_error_ = saved.error().message;
  }
}

ServiceFigures Daemon::Figures() const {
  const InputQueueStats& stats = queue_->stats();
  ServiceFigures figures;
  figures.lidar_rate_hz = rates_->lidar_hz;
  figures.can_rate_hz = rates_->can_hz;
  figures.lidar_received = stats.datagrams.load();
  figures.lidar_dropped = stats.datagrams_dropped.load() + stats.datagrams_too_long.load() + lidar_->source_drops();
  figures.can_received = board_->health().can_frames;
  figures.can_dropped = stats.frames_dropped.load() + (can_ ? can_->source_drops() : 0);
  figures.clients = server_ ? server_->stats().clients.load() : 0;
  figures.malformed_requests = server_ ? server_->stats().malformed_requests.load() : 0;
  figures.rss_bytes = ResidentBytes();
  figures.uptime_s = static_cast<double>(MonotonicNs() - started_ns_) * kSecondsPerNs;
  figures.now_ns = ClockNs(CLOCK_REALTIME);
  figures.gpio = gpio_->Health(figures.now_ns);
  const std::lock_guard lock(error_mutex_);
  figures.last_error = last_error_;
  return figures;
}

std::string Daemon::StatusLine() const {
  const localization::LocalizationFix fix = board_->fix();
  char line[160];
  std::snprintf(line, sizeof(line), "%s, lidar %.0f/s, can %.0f/s, %" PRIu32 " clients",
                std::string(localization::LocalizerStateName(fix.state)).c_str(), rates_->lidar_hz.load(),
                rates_->can_hz.load(), server_->stats().clients.load());
  std::string status = line;
  if (gpio_->has_pps()) {
    const api::v1::GpioHealth gpio = gpio_->Health(ClockNs(CLOCK_REALTIME));
    status += ", pps " + api::v1::PpsState_Name(gpio.pps_state());
  }
  return status;
}

}  // namespace flat2d::daemon
