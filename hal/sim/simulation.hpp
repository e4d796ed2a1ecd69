// One simulated drive end to end: a world and a drive in, Velodyne packets, CAN frames and
// ground-truth poses out, in time order, to any number of sinks (files, a live UDP stream,
// a counter). This is what `flat2d-sim` runs and what the demo and benchmarks use as their
// data source (issue 5, item 6).
//
// Steps of RunSimulation: (1) resolve the world (a built-in name, a .textproto file or a
// SceneDescription) and build the Scene and the drive's Trajectory; (2) check the options
// (drive index, duration, rates) with errors that say what is allowed; (3) create the LiDAR
// and odometry simulators, both seeded from `seed` so that equal options give equal bytes;
// (4) hand every sink the setup (Begin), then merge the three time-ordered streams - LiDAR
// datagrams, CAN frames and truth poses at `truth_rate_hz` - by their absolute time (ties:
// truth, then CAN, then LiDAR) and hand each event to every sink; (5) Finish the sinks and
// return counts and timings. The first sink error stops the run and is returned.
//
// Time: drive time 0 is `start_epoch_ns` (Unix ns); world time = drive time +
// drive.world_time_offset_s (scene.proto).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "hal/can/can_frame.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/net/udp_datagram.hpp"
#include "hal/sim/scene.hpp"
#include "hal/sim/lidar_options.hpp"
#include "hal/sim/odometry_noise.hpp"
#include "hal/sim/trajectory.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::sim {

inline constexpr std::uint32_t kVelodyneDefaultAddress = 0xC0A801C9;  // 192.168.1.201
inline constexpr double kMinTruthRateHz = 100.0;

struct SimulationOptions {
  // A built-in world name (worlds.hpp), a path to a SceneDescription text file, or the
  // description itself.
  std::variant<std::string, SceneDescription> world = std::string("campus");
  int drive = 0;                       // index into the world's drives
  std::uint64_t seed = 1;
  std::optional<double> duration_s;    // default: the drive's duration
  // The sensor: model, rotation_hz, mounting, range noise, dropouts, ranges, GNSS fixes in
  // the position packets (lidar_options.hpp). Its start_epoch_ns is replaced by the one
  // below, which sets every clock of the run.
  LidarOptions lidar = DefaultLidarOptions(velodyne::Model::kHdl32e);
  OdometryNoise odometry_noise = OdometryNoise::Mems();
  double truth_rate_hz = 200.0;        // >= kMinTruthRateHz
  TimeNs start_epoch_ns = kDefaultStartEpochNs;  // Unix time of drive time 0
  // The packets as the sensor sends them: from 192.168.1.201 to the broadcast address,
  // data to 2368 and position to 8308, each from the same port it is sent to.
  std::uint32_t source_address = kVelodyneDefaultAddress;
  std::uint32_t destination_address = 0xFFFFFFFF;
  std::uint16_t data_port = 2368;
  std::uint16_t position_port = 8308;
  std::string can_interface = "can0";
};

// What a sink may need before the first event (the file sink writes the truth map and DBC).
struct SimulationSetup {
  const SimulationOptions& options;
  const Scene& scene;
  const Drive& drive;
  const Trajectory& trajectory;
  TimeNs start_ns = 0;  // absolute time of drive time 0
  TimeNs end_ns = 0;    // absolute time of the last event
};

// Receives the merged stream. Payload spans are valid only during the call.
class SimulationSink {
 public:
  virtual ~SimulationSink() = default;
  virtual Status Begin(const SimulationSetup& /*setup*/) { return Status::Ok(); }
  virtual Status OnDatagram(const net::UdpDatagram& /*datagram*/) { return Status::Ok(); }
  virtual Status OnCanFrame(const can::CanFrame& /*frame*/) { return Status::Ok(); }
  // world_T_vehicle at absolute time `time_ns` (state.drive_time_s is the drive time).
  virtual Status OnTruthPose(TimeNs /*time_ns*/, const VehicleState& /*state*/) {
    return Status::Ok();
  }
  virtual Status Finish() { return Status::Ok(); }

 protected:
  SimulationSink() = default;
  SimulationSink(const SimulationSink&) = default;
  SimulationSink& operator=(const SimulationSink&) = default;
};

struct SimulationSummary {
  std::string world;
  std::string drive;
  double drive_duration_s = 0.0;  // the drive's own length in time
  double drive_length_m = 0.0;
  std::uint64_t data_packets = 0;
  std::uint64_t position_packets = 0;
  std::uint64_t can_frames = 0;
  std::uint64_t truth_poses = 0;
  double simulated_s = 0.0;
  double wall_s = 0.0;
};

// The scene description a world argument names: a built-in world, else a text-format
// SceneDescription file. Errors list the built-in names.
Result<SceneDescription> ResolveWorld(const std::string& name_or_path);

// A drive of a world as `flat2d-sim --list` shows it.
struct DriveInfo {
  int index = 0;
  std::string name;
  std::string description;
  double duration_s = 0.0;
  double length_m = 0.0;
  bool loop = false;
};

// The world's drives with their durations and lengths (builds the scene and each
// trajectory, so a broken world or drive is an error here, not halfway through a run).
Result<std::vector<DriveInfo>> DescribeDrives(const SceneDescription& world);

Result<SimulationSummary> RunSimulation(const SimulationOptions& options,
                                        std::span<SimulationSink* const> sinks);

// "vlp16" | "hdl32e" | "vlp32c" (lower case, as the CLI takes them).
std::optional<velodyne::Model> ParseSensorName(std::string_view name);
// "mems" | "fog" | "none": the presets of odometry_noise.hpp.
std::optional<OdometryNoise> OdometryNoisePreset(std::string_view name);

}  // namespace flat2d::hal::sim
