// A simulated Velodyne VLP-16, HDL-32E or VLP-32C on a vehicle driving a Trajectory through a
// Scene: the UDP payloads the sensor would send, byte-exact, in the order a host receives
// them, with their capture times.
//
// Data packets come from DataPacketSimulator (lidar_data_packets.hpp: ray casting at every
// laser's firing time and pose, noise, dropouts, range limits), position packets from
// PositionPacketSimulator (lidar_position_packets.hpp: device time and $GPRMC of an optional
// GNSS). Next() merges the two streams by capture time. Time: Unix time = start_epoch_ns +
// drive time; a data packet is captured capture_latency_us after its last firing. The
// output depends only on the scene, trajectory, options and seed: the same inputs give
// the same bytes. After Create nothing allocates.
//
//   auto sim = LidarSimulator::Create(scene, trajectory, DefaultLidarOptions(Model::kHdl32e), 7);
//   while (sim->next_capture_time_ns() < end_ns) {
//     const SimulatedPacket& p = sim->Next();
//     pcap.Write(p.capture_time_ns, p.destination_port, p.payload);
//   }
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/sim/lidar_options.hpp"
#include "hal/sim/scene.hpp"
#include "hal/sim/trajectory.hpp"
#include "hal/velodyne/laser_table.hpp"

namespace flat2d::hal::sim {

enum class LidarPacketKind : std::uint8_t { kData, kPosition };

struct SimulatedPacket {
  LidarPacketKind kind = LidarPacketKind::kData;
  TimeNs capture_time_ns = 0;  // Unix time a host receives it (pcap timestamp)
  TimeNs device_time_ns = 0;   // Unix time of its timestamp: first firing, or assembly
  double drive_time_s = 0.0;   // the same instant in drive time
  std::uint16_t destination_port = 0;  // 2368 (data) or 8308 (position)
  std::uint64_t index = 0;             // 0, 1, 2, ... per kind
  std::span<const std::uint8_t> payload;  // 1206 or 512 bytes; valid until the next call
};

class LidarSimulator {
 public:
  // Validates the options. `scene` and `trajectory` must outlive the simulator.
  static Result<LidarSimulator> Create(const Scene& scene, const Trajectory& trajectory,
                                       const LidarOptions& options, std::uint64_t seed);

  LidarSimulator(LidarSimulator&&) noexcept;
  LidarSimulator& operator=(LidarSimulator&&) noexcept;
  ~LidarSimulator();

  // The next packet of either kind, in capture-time order (data first on a tie).
  const SimulatedPacket& Next();
  // Capture time of the packet Next() returns.
  TimeNs next_capture_time_ns() const;

  // The two streams alone (not to be mixed with Next()).
  const SimulatedPacket& NextDataPacket();
  const SimulatedPacket& NextPositionPacket();

  // Drive time <-> Unix time of this run.
  TimeNs UnixTimeNs(double drive_time_s) const;
  double DriveTimeS(TimeNs unix_time_ns) const;

  const LidarOptions& options() const;
  // The calibration the packets are encoded with: give it to the decoder.
  const velodyne::LaserTable& laser_table() const;
  // Packets of each kind returned so far.
  std::uint64_t data_packets() const;
  std::uint64_t position_packets() const;

 private:
  struct Impl;
  explicit LidarSimulator(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace flat2d::hal::sim
