#include "hal/sim/lidar_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hal/sim/lidar_data_packets.hpp"
#include "hal/sim/lidar_position_packets.hpp"
#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::sim {

struct LidarSimulator::Impl {
  Impl(const Scene& scene, const Trajectory& trajectory, const LidarOptions& opts, std::uint64_t seed)
      : options(opts),
        data(scene, trajectory, opts, seed),
        position(trajectory, opts, seed),
        latency_ns(std::llround(opts.capture_latency_us * 1e3)) {
    const TimeNs start_ns = std::llround(opts.start_drive_time_s * 1e9);
    next_data = FirstIndexAtOrAfter(start_ns, data.packet_period_ns(), 0);
    next_position = FirstIndexAtOrAfter(start_ns, position.AssemblyTimeNs(1) - position.AssemblyTimeNs(0),
                                        position.AssemblyTimeNs(0));
  }

  // Smallest i with first + i x period >= t.
  static std::uint64_t FirstIndexAtOrAfter(TimeNs t, TimeNs period, TimeNs first) {
    if (t <= first) return 0;
    return static_cast<std::uint64_t>((t - first + period - 1) / period);
  }

  TimeNs DataCaptureNs() const {
    return options.start_epoch_ns + data.FirstFiringNs(next_data) + data.packet_period_ns() + latency_ns;
  }
  TimeNs PositionCaptureNs() const {
    if (!options.position_packets) return std::numeric_limits<TimeNs>::max();
    return options.start_epoch_ns + position.AssemblyTimeNs(next_position) + latency_ns;
  }

  LidarOptions options;
  DataPacketSimulator data;
  PositionPacketSimulator position;
  TimeNs latency_ns;
  std::uint64_t next_data = 0;
  std::uint64_t next_position = 0;
  velodyne::DataPacketBytes data_bytes{};
  velodyne::PositionPacketBytes position_bytes{};
  SimulatedPacket packet;
};

Result<LidarSimulator> LidarSimulator::Create(const Scene& scene, const Trajectory& trajectory,
                                              const LidarOptions& options, std::uint64_t seed) {
  if (Status status = ValidateLidarOptions(options); !status) return status.error();
  return LidarSimulator(std::make_unique<Impl>(scene, trajectory, options, seed));
}

LidarSimulator::LidarSimulator(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LidarSimulator::LidarSimulator(LidarSimulator&&) noexcept = default;
LidarSimulator& LidarSimulator::operator=(LidarSimulator&&) noexcept = default;
LidarSimulator::~LidarSimulator() = default;

const SimulatedPacket& LidarSimulator::Next() {
  if (impl_->PositionCaptureNs() < impl_->DataCaptureNs()) return NextPositionPacket();
  return NextDataPacket();
}

TimeNs LidarSimulator::next_capture_time_ns() const {
  return std::min(impl_->DataCaptureNs(), impl_->PositionCaptureNs());
}

const SimulatedPacket& LidarSimulator::NextDataPacket() {
  Impl& s = *impl_;
  SimulatedPacket& p = s.packet;
  const std::uint64_t k = s.next_data;
  p.capture_time_ns = s.DataCaptureNs();
  s.data.Simulate(k, s.data_bytes);
  p.kind = LidarPacketKind::kData;
  p.device_time_ns = s.options.start_epoch_ns + s.data.FirstFiringNs(k);
  p.drive_time_s = static_cast<double>(s.data.FirstFiringNs(k)) * 1e-9;
  p.destination_port = velodyne::kDefaultDataPort;
  p.index = k;
  p.payload = s.data_bytes;
  ++s.next_data;
  return p;
}

const SimulatedPacket& LidarSimulator::NextPositionPacket() {
  Impl& s = *impl_;
  SimulatedPacket& p = s.packet;
  const std::uint64_t j = s.next_position;
  const TimeNs drive_ns = s.position.AssemblyTimeNs(j);
  s.position.Simulate(j, s.position_bytes);
  p.kind = LidarPacketKind::kPosition;
  p.device_time_ns = s.options.start_epoch_ns + drive_ns;
  p.capture_time_ns = p.device_time_ns + s.latency_ns;
  p.drive_time_s = static_cast<double>(drive_ns) * 1e-9;
  p.destination_port = velodyne::kDefaultPositionPort;
  p.index = j;
  p.payload = s.position_bytes;
  ++s.next_position;
  return p;
}

TimeNs LidarSimulator::UnixTimeNs(double drive_time_s) const {
  return impl_->options.start_epoch_ns + std::llround(drive_time_s * 1e9);
}

double LidarSimulator::DriveTimeS(TimeNs unix_time_ns) const {
  return static_cast<double>(unix_time_ns - impl_->options.start_epoch_ns) * 1e-9;
}

const LidarOptions& LidarSimulator::options() const { return impl_->options; }
const velodyne::LaserTable& LidarSimulator::laser_table() const { return impl_->data.laser_table(); }
std::uint64_t LidarSimulator::data_packets() const { return impl_->next_data; }
std::uint64_t LidarSimulator::position_packets() const { return impl_->next_position; }

}  // namespace flat2d::hal::sim
