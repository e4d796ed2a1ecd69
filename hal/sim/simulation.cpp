#include "hal/sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "hal/config/text_proto.hpp"
#include "hal/sim/lidar_simulator.hpp"
#include "hal/sim/odometry_simulator.hpp"
#include "hal/sim/worlds.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kMaxTruthRateHz = 10'000.0;
// About 11.6 days: beyond any drive, and far from int64 nanosecond overflow.
constexpr double kMaxDurationS = 1e6;

std::string JoinNames(std::span<const std::string_view> names) {
  std::string joined;
  for (const std::string_view name : names) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

Status CheckOptions(const SimulationOptions& options, const SceneDescription& world) {
  const int drives = world.drives_size();
  if (drives == 0) return MakeError("world '" + world.name() + "' has no drives");
  if (options.drive < 0 || options.drive >= drives) {
    return MakeError("drive " + std::to_string(options.drive) + " out of range: world '" +
                     world.name() + "' has " + std::to_string(drives) + " drive" +
                     (drives == 1 ? "" : "s") + " (0-" + std::to_string(drives - 1) + ")");
  }
  if (options.duration_s &&
      !(*options.duration_s > 0.0 && *options.duration_s <= kMaxDurationS)) {
    return MakeError("duration must be positive and at most 1e6 s, got " +
                     std::to_string(*options.duration_s));
  }
  if (Status lidar = ValidateLidarOptions(options.lidar); !lidar) return lidar;
  if (!(options.truth_rate_hz >= kMinTruthRateHz && options.truth_rate_hz <= kMaxTruthRateHz)) {
    return MakeError("truth rate must be 100-10000 Hz, got " +
                     std::to_string(options.truth_rate_hz));
  }
  if (options.start_epoch_ns < 0) return MakeError("start time must not be before 1970");
  return Status::Ok();
}

// Length of the path the vehicle drives in [0, duration_s], from 10 Hz samples (an arc
// sampled that finely is within 0.1% of its length at the drives' corner radii).
double DrivenLength(const Trajectory& trajectory, double duration_s) {
  constexpr double kStepS = 0.1;
  double length_m = 0.0;
  Eigen::Vector3d previous = trajectory.At(0.0).world_T_vehicle.translation();
  for (double t = kStepS; t < duration_s + kStepS; t += kStepS) {
    const Eigen::Vector3d now = trajectory.At(std::min(t, duration_s)).world_T_vehicle.translation();
    length_m += (now - previous).norm();
    previous = now;
  }
  return length_m;
}

// Hands each event to every sink; the first error stops the run.
class Fanout {
 public:
  explicit Fanout(std::span<SimulationSink* const> sinks) : sinks_(sinks) {}

  template <typename Call>
  Status ForEach(Call&& call) {
    for (SimulationSink* sink : sinks_) {
      if (Status status = call(*sink); !status) return status;
    }
    return Status::Ok();
  }

 private:
  std::span<SimulationSink* const> sinks_;
};

// Truth poses at t_k = start + k / rate for every t_k <= end: integer nanoseconds from the
// index, so the rate does not drift by accumulated rounding.
class TruthStream {
 public:
  TruthStream(const Trajectory& trajectory, const SimulationOptions& options, TimeNs end_ns)
      : trajectory_(trajectory), start_ns_(options.start_epoch_ns), end_ns_(end_ns),
        rate_hz_(options.truth_rate_hz) {}

  std::optional<TimeNs> NextTime() const {
    const TimeNs time_ns = TimeOf(next_);
    return time_ns <= end_ns_ ? std::optional<TimeNs>(time_ns) : std::nullopt;
  }

  Status Emit(Fanout& fanout) {
    const TimeNs time_ns = TimeOf(next_++);
    const VehicleState state = trajectory_.At(static_cast<double>(time_ns - start_ns_) * 1e-9);
    return fanout.ForEach([&](SimulationSink& sink) { return sink.OnTruthPose(time_ns, state); });
  }

 private:
  TimeNs TimeOf(std::uint64_t k) const {
    return start_ns_ + std::llround(static_cast<double>(k) * 1e9 / rate_hz_);
  }

  const Trajectory& trajectory_;
  TimeNs start_ns_;
  TimeNs end_ns_;
  double rate_hz_;
  std::uint64_t next_ = 0;
};

constexpr TimeNs kNever = std::numeric_limits<TimeNs>::max();

// The packet as a UDP datagram from the sensor's address and port to the configured ones.
net::UdpDatagram ToDatagram(const SimulatedPacket& packet, const SimulationOptions& options) {
  const std::uint16_t port =
      packet.kind == LidarPacketKind::kData ? options.data_port : options.position_port;
  return {packet.capture_time_ns, {options.source_address, port},
          {options.destination_address, port}, packet.payload};
}

// The three time-ordered streams merged by time, up to end_ns inclusive; ties go to truth,
// then CAN, then LiDAR.
Status MergeStreams(TruthStream& truth, OdometrySimulator& odometry, LidarSimulator& lidar,
                    const SimulationOptions& options, TimeNs end_ns, Fanout& fanout,
                    SimulationSummary& summary) {
  for (;;) {
    const TimeNs truth_ns = truth.NextTime().value_or(kNever);
    const TimeNs can_ns = odometry.NextTime().value_or(kNever);
    const TimeNs lidar_ns = lidar.next_capture_time_ns() <= end_ns ? lidar.next_capture_time_ns() : kNever;
    const TimeNs next_ns = std::min({truth_ns, can_ns, lidar_ns});
    if (next_ns == kNever) return Status::Ok();
    Status status;
    if (truth_ns == next_ns) {
      status = truth.Emit(fanout);
      ++summary.truth_poses;
    } else if (can_ns == next_ns) {
      const std::optional<can::CanFrame> frame = odometry.Next();
      status = fanout.ForEach([&](SimulationSink& sink) { return sink.OnCanFrame(*frame); });
      ++summary.can_frames;
    } else {
      const SimulatedPacket& packet = lidar.Next();
      const net::UdpDatagram datagram = ToDatagram(packet, options);
      status = fanout.ForEach([&](SimulationSink& sink) { return sink.OnDatagram(datagram); });
      ++(packet.kind == LidarPacketKind::kData ? summary.data_packets : summary.position_packets);
    }
    if (!status) return status;
  }
}

}  // namespace

Result<SceneDescription> ResolveWorld(const std::string& name_or_path) {
  if (auto built_in = BuiltInWorld(name_or_path); built_in.ok()) return std::move(*built_in);
  const std::filesystem::path path(name_or_path);
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return MakeError("unknown world '" + name_or_path + "': built-in worlds are " +
                     JoinNames(BuiltInWorldNames()) + ", or give a .textproto file");
  }
  SceneDescription description;
  if (Status loaded = config::LoadTextProto(path, description); !loaded) return loaded.error();
  if (description.name().empty()) description.set_name(path.stem().string());
  return description;
}

Result<SimulationSummary> RunSimulation(const SimulationOptions& options,
                                        std::span<SimulationSink* const> sinks) {
  const auto wall_start = std::chrono::steady_clock::now();
  Result<SceneDescription> world =
      std::holds_alternative<SceneDescription>(options.world)
          ? Result<SceneDescription>(std::get<SceneDescription>(options.world))
          : ResolveWorld(std::get<std::string>(options.world));
  if (!world.ok()) return world.error();
  if (Status checked = CheckOptions(options, *world); !checked) return checked.error();

  auto scene = Scene::Create(*world);
  if (!scene.ok()) return MakeError("world '" + world->name() + "': " + scene.error().message);
  const Drive& drive = world->drives(options.drive);
  auto trajectory = Trajectory::Create(*scene, drive);
  if (!trajectory.ok()) {
    return MakeError("world '" + world->name() + "' drive " + std::to_string(options.drive) +
                     ": " + trajectory.error().message);
  }
  const double duration_s = options.duration_s.value_or(trajectory->duration_s());
  const TimeNs end_ns = options.start_epoch_ns + std::llround(duration_s * 1e9);

  OdometrySimOptions odometry_options;
  odometry_options.start_epoch_ns = options.start_epoch_ns;
  odometry_options.duration_s = duration_s;
  odometry_options.noise = options.odometry_noise;
  odometry_options.interface_name = options.can_interface;
  auto odometry = OdometrySimulator::Create(*trajectory, odometry_options, options.seed);
  if (!odometry.ok()) return odometry.error();
  LidarOptions lidar_options = options.lidar;
  lidar_options.start_epoch_ns = options.start_epoch_ns;
  auto lidar = LidarSimulator::Create(*scene, *trajectory, lidar_options, options.seed);
  if (!lidar.ok()) return lidar.error();
  TruthStream truth(*trajectory, options, end_ns);

  SimulationSummary summary;
  summary.world = world->name();
  summary.drive = drive.name();
  summary.drive_duration_s = trajectory->duration_s();
  summary.drive_length_m = DrivenLength(*trajectory, trajectory->duration_s());
  summary.simulated_s = duration_s;

  Fanout fanout(sinks);
  const SimulationSetup setup{options, *scene, drive, *trajectory, options.start_epoch_ns, end_ns};
  if (Status begun = fanout.ForEach([&](SimulationSink& s) { return s.Begin(setup); }); !begun) {
    return begun.error();
  }
  if (Status merged = MergeStreams(truth, *odometry, *lidar, options, end_ns, fanout, summary); !merged) {
    return merged.error();
  }
  if (Status finished = fanout.ForEach([](SimulationSink& s) { return s.Finish(); }); !finished) {
    return finished.error();
  }
  summary.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return summary;
}

Result<std::vector<DriveInfo>> DescribeDrives(const SceneDescription& world) {
  auto scene = Scene::Create(world);
  if (!scene.ok()) return scene.error();
  std::vector<DriveInfo> drives;
  for (int i = 0; i < world.drives_size(); ++i) {
    const Drive& drive = world.drives(i);
    auto trajectory = Trajectory::Create(*scene, drive);
    if (!trajectory.ok()) {
      return MakeError("drive " + std::to_string(i) + ": " + trajectory.error().message);
    }
    drives.push_back({i, drive.name(), drive.description(), trajectory->duration_s(),
                      DrivenLength(*trajectory, trajectory->duration_s()), drive.loop()});
  }
  return drives;
}

std::optional<velodyne::Model> ParseSensorName(std::string_view name) {
  return velodyne::ParseModelName(name);
}

std::optional<OdometryNoise> OdometryNoisePreset(std::string_view name) {
  if (name == "mems") return OdometryNoise::Mems();
  if (name == "fog") return OdometryNoise::Fog();
  if (name == "none") return OdometryNoise::None();
  return std::nullopt;
}

}  // namespace flat2d::hal::sim
