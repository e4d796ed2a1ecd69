#include "daemon/config/daemon_config.hpp"

#include <string>
#include <type_traits>

#include "daemon/service/gpio_wiring.hpp"
#include "hal/config/text_proto.hpp"
#include "hal/net/ipv4.hpp"
#include "localization/localizer/localizer_config.hpp"
#include "localization/odometry/odometry_config.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::daemon {
namespace {

constexpr std::uint32_t kVelodyneDataPort = 2368;
constexpr std::uint32_t kVelodynePositionPort = 8308;
constexpr std::uint32_t kDefaultReceiveBuffer = 4u << 20;
constexpr std::uint32_t kDefaultRing = 4096;
constexpr std::uint32_t kMaxRing = 1u << 16;
constexpr const char* kDefaultUnixSocket = "/run/flat2d/api.sock";
constexpr std::uint32_t kDefaultUnixMode = 0660;
constexpr std::uint32_t kDefaultMaxClients = 64;
constexpr std::uint32_t kMaxClients = 1024;
constexpr std::uint32_t kDefaultMaxMessage = 4096;
constexpr std::uint32_t kMinMessage = 256;
constexpr std::uint32_t kMaxMessage = 1u << 20;

// Proto3 scalars have no presence: zero means "not set", and takes the documented default.
template <typename Message, typename Value>
void DefaultIfZero(Message& message, Value (Message::*get)() const, void (Message::*set)(Value),
                   std::type_identity_t<Value> fallback) {
  if ((message.*get)() == Value{}) (message.*set)(fallback);
}

void FillDefaults(DaemonConfig& config) {
  LidarSource& lidar = *config.mutable_lidar();
  DefaultIfZero(lidar, &LidarSource::ring_datagrams, &LidarSource::set_ring_datagrams, kDefaultRing);
  if (lidar.has_udp()) {
    UdpLidarSource& udp = *lidar.mutable_udp();
    if (udp.bind_address().empty()) udp.set_bind_address("0.0.0.0");
    DefaultIfZero(udp, &UdpLidarSource::port, &UdpLidarSource::set_port, kVelodyneDataPort);
    DefaultIfZero(udp, &UdpLidarSource::position_port, &UdpLidarSource::set_position_port, kVelodynePositionPort);
    DefaultIfZero(udp, &UdpLidarSource::receive_buffer_bytes, &UdpLidarSource::set_receive_buffer_bytes, kDefaultReceiveBuffer);
  }
  if (lidar.has_pcap()) DefaultIfZero(*lidar.mutable_pcap(), &PcapLidarSource::rate, &PcapLidarSource::set_rate, 1.0);
  DefaultIfZero(*config.mutable_can(), &CanSource::ring_frames, &CanSource::set_ring_frames, kDefaultRing);
  ApiConfig& api = *config.mutable_api();
  if (api.unix_socket().empty()) api.set_unix_socket(kDefaultUnixSocket);
  DefaultIfZero(api, &ApiConfig::unix_mode, &ApiConfig::set_unix_mode, kDefaultUnixMode);
  DefaultIfZero(api, &ApiConfig::max_clients, &ApiConfig::set_max_clients, kDefaultMaxClients);
  DefaultIfZero(api, &ApiConfig::max_message_bytes, &ApiConfig::set_max_message_bytes, kDefaultMaxMessage);
  DefaultIfZero(api, &ApiConfig::max_subscribe_hz, &ApiConfig::set_max_subscribe_hz, 100.0);
  if (config.has_initial_pose()) {
    InitialPose& initial = *config.mutable_initial_pose();
    DefaultIfZero(initial, &InitialPose::sigma_m, &InitialPose::set_sigma_m, 1.0);
    DefaultIfZero(initial, &InitialPose::sigma_rad, &InitialPose::set_sigma_rad, 0.1);
  }
  Persistence& persistence = *config.mutable_persistence();
  DefaultIfZero(persistence, &Persistence::period_s, &Persistence::set_period_s, 1.0);
  DefaultIfZero(persistence, &Persistence::warm_start_sigma_m, &Persistence::set_warm_start_sigma_m, 2.0);
  DefaultIfZero(persistence, &Persistence::warm_start_sigma_rad, &Persistence::set_warm_start_sigma_rad, 0.2);
  GpioConfig& gpio = *config.mutable_gpio();
  if (gpio.has_pose_valid()) {
    PoseValidOutputConfig& output = *gpio.mutable_pose_valid();
    DefaultIfZero(output, &PoseValidOutputConfig::min_on_ms, &PoseValidOutputConfig::set_min_on_ms, 500);
    DefaultIfZero(output, &PoseValidOutputConfig::min_off_ms, &PoseValidOutputConfig::set_min_off_ms, 1000);
  }
  if (gpio.has_pps()) {
    PpsInputConfig& pps = *gpio.mutable_pps();
    DefaultIfZero(pps, &PpsInputConfig::window_pulses, &PpsInputConfig::set_window_pulses, 32);
    DefaultIfZero(pps, &PpsInputConfig::lock_pulses, &PpsInputConfig::set_lock_pulses, 8);
  }
  DefaultIfZero(config, &DaemonConfig::watchdog_stall_s, &DaemonConfig::set_watchdog_stall_s, 2.0);
}

void Resolve(const std::filesystem::path& folder, std::string& path) {
  if (!path.empty() && std::filesystem::path(path).is_relative()) path = (folder / path).lexically_normal().string();
}

void ResolvePaths(const std::filesystem::path& folder, DaemonConfig& config) {
  if (config.lidar().has_pcap()) Resolve(folder, *config.mutable_lidar()->mutable_pcap()->mutable_path());
  if (config.can().has_candump()) Resolve(folder, *config.mutable_can()->mutable_candump()->mutable_path());
  Resolve(folder, *config.mutable_dbc());
  Resolve(folder, *config.mutable_odometry_config());
  Resolve(folder, *config.mutable_grid_config());
  Resolve(folder, *config.mutable_localizer_config());
  Resolve(folder, *config.mutable_map());
  Resolve(folder, *config.mutable_persistence()->mutable_l2g_path());
}

Error FieldError(std::string_view source, std::string_view field, std::string_view what) {
  return MakeError(std::string(source) + ": " + std::string(field) + ": " + std::string(what));
}

Status ValidateSources(const DaemonConfig& config, std::string_view source) {
  const LidarSource& lidar = config.lidar();
  if (!lidar.has_udp() && !lidar.has_pcap()) return FieldError(source, "lidar", "set udp or pcap");
  if (lidar.has_udp()) {
    if (!hal::net::ParseIpv4(lidar.udp().bind_address())) {
      return FieldError(source, "lidar.udp.bind_address", "not an IPv4 address: " + lidar.udp().bind_address());
    }
    if (lidar.udp().port() > 65535) return FieldError(source, "lidar.udp.port", "above 65535");
    if (lidar.udp().position_port() > 65535) return FieldError(source, "lidar.udp.position_port", "above 65535");
    if (!lidar.udp().sensor_address().empty() && !hal::net::ParseIpv4(lidar.udp().sensor_address())) {
      return FieldError(source, "lidar.udp.sensor_address", "not an IPv4 address: " + lidar.udp().sensor_address());
    }
  }
  if (lidar.has_pcap()) {
    if (lidar.pcap().path().empty()) return FieldError(source, "lidar.pcap.path", "empty");
    if (!(lidar.pcap().rate() > 0.0 && lidar.pcap().rate() <= 1000.0)) {
      return FieldError(source, "lidar.pcap.rate", "must be in (0, 1000]");
    }
  }
  if (lidar.ring_datagrams() > kMaxRing) return FieldError(source, "lidar.ring_datagrams", "above 65536");
  const CanSource& can = config.can();
  if (!can.has_socketcan() && !can.has_candump()) return FieldError(source, "can", "set socketcan or candump");
  if (can.has_socketcan() && can.socketcan().interface().empty()) {
    return FieldError(source, "can.socketcan.interface", "empty");
  }
  if (can.has_candump() && can.candump().path().empty()) return FieldError(source, "can.candump.path", "empty");
  if (can.ring_frames() > kMaxRing) return FieldError(source, "can.ring_frames", "above 65536");
  return Status::Ok();
}

Status ValidateApi(const ApiConfig& api, std::string_view source) {
  if (api.unix_mode() > 0777) return FieldError(source, "api.unix_mode", "not a permission mode (at most 0777)");
  if (!api.tcp_address().empty()) {
    if (!hal::net::ParseIpv4(api.tcp_address())) {
      return FieldError(source, "api.tcp_address", "not an IPv4 address: " + api.tcp_address());
    }
    if (api.tcp_port() == 0 || api.tcp_port() > 65535) return FieldError(source, "api.tcp_port", "must be 1..65535");
  }
  if (api.max_clients() > kMaxClients) return FieldError(source, "api.max_clients", "above 1024");
  if (api.max_message_bytes() < kMinMessage || api.max_message_bytes() > kMaxMessage) {
    return FieldError(source, "api.max_message_bytes", "must be 256..1048576");
  }
  if (!(api.max_subscribe_hz() > 0.0 && api.max_subscribe_hz() <= 1000.0)) {
    return FieldError(source, "api.max_subscribe_hz", "must be in (0, 1000]");
  }
  return Status::Ok();
}

Status ValidateGpioLine(const GpioLine& line, std::string_view source, const std::string& field) {
  if (line.chip().empty()) return FieldError(source, field + ".chip", "required");
  return Status::Ok();
}

bool SameLine(const GpioLine& a, const GpioLine& b) {
  return a.chip() == b.chip() && (a.name().empty() && b.name().empty() ? a.offset() == b.offset() : a.name() == b.name());
}

Status ValidateGpio(const GpioConfig& gpio, std::string_view source) {
  if (gpio.has_pose_valid()) {
    if (Status line = ValidateGpioLine(gpio.pose_valid().line(), source, "gpio.pose_valid.line"); !line.ok()) return line;
  }
  if (gpio.has_pps()) {
    if (Status line = ValidateGpioLine(gpio.pps().line(), source, "gpio.pps.line"); !line.ok()) return line;
    if (Status clock = hal::gpio::ValidatePpsClockOptions(PpsClockOptionsFor(gpio.pps())); !clock.ok()) {
      return FieldError(source, "gpio.pps", clock.error().message);
    }
  }
  if (gpio.has_pose_valid() && gpio.has_pps() && SameLine(gpio.pose_valid().line(), gpio.pps().line())) {
    return FieldError(source, "gpio", "pose_valid and pps name the same line");
  }
  return Status::Ok();
}

}  // namespace

Status ValidateDaemonConfig(const DaemonConfig& config, std::string_view source) {
  if (Status sources = ValidateSources(config, source); !sources.ok()) return sources;
  if (Status api = ValidateApi(config.api(), source); !api.ok()) return api;
  for (const auto& [field, value] : {std::pair{"dbc", &config.dbc()}, std::pair{"odometry_config", &config.odometry_config()},
                                     std::pair{"grid_config", &config.grid_config()},
                                     std::pair{"localizer_config", &config.localizer_config()},
                                     std::pair{"map", &config.map()}}) {
    if (value->empty()) return FieldError(source, field, "required");
  }
  const InitialPose& initial = config.initial_pose();
  if (config.has_initial_pose() && (!(initial.sigma_m() > 0.0) || !(initial.sigma_rad() > 0.0))) {
    return FieldError(source, "initial_pose", "sigma_m and sigma_rad must be positive");
  }
  const Persistence& persistence = config.persistence();
  if (!(persistence.period_s() > 0.0)) return FieldError(source, "persistence.period_s", "must be positive");
  if (!(persistence.warm_start_sigma_m() > 0.0) || !(persistence.warm_start_sigma_rad() > 0.0)) {
    return FieldError(source, "persistence", "warm_start_sigma_m and warm_start_sigma_rad must be positive");
  }
  if (!(config.watchdog_stall_s() > 0.0)) return FieldError(source, "watchdog_stall_s", "must be positive");
  return ValidateGpio(config.gpio(), source);
}

Result<DaemonConfig> LoadDaemonConfig(const std::filesystem::path& path) {
  DaemonConfig config;
  if (Status loaded = hal::config::LoadTextProto(path, config); !loaded.ok()) return loaded.error();
  FillDefaults(config);
  ResolvePaths(std::filesystem::absolute(path).parent_path(), config);
  if (Status valid = ValidateDaemonConfig(config, path.string()); !valid.ok()) return valid.error();
  return config;
}

Result<DaemonInputs> LoadDaemonInputs(const std::filesystem::path& config_path) {
  auto config = LoadDaemonConfig(config_path);
  if (!config.ok()) return config.error();
  auto dbc = hal::can::LoadDbc(config->dbc());
  if (!dbc.ok()) return dbc.error();
  auto odometry = localization::LoadOdometryConfig(config->odometry_config());
  if (!odometry.ok()) return odometry.error();
  auto grid = maps::LoadStructureGridOptions(config->grid_config());
  if (!grid.ok()) return grid.error();
  auto localizer = localization::LoadLocalizerOptions(config->localizer_config());
  if (!localizer.ok()) return localizer.error();
  auto map = maps::PriorMapReader::Open(config->map(), localizer->map_cache_tiles);
  if (!map.ok()) return map.error();
  return DaemonInputs{.config = std::move(*config),
                      .dbc = std::move(*dbc),
                      .odometry = std::move(*odometry),
                      .grid = std::move(*grid),
                      .localizer = std::move(*localizer),
                      .map = std::make_unique<maps::PriorMapReader>(std::move(*map))};
}

}  // namespace flat2d::daemon
