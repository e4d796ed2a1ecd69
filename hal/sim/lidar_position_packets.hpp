// The simulated Velodyne's 512-byte position packets (port 8308): sent every
// position_period_us (the shared captures: VLP-16 146/s, HDL-32E 205/s), each stamped with
// the device time and carrying the last $GPRMC sentence of an optional GNSS receiver.
//
// The receiver reports once per PPS second S: UTC time S (whole seconds, the time of the
// PPS edge) and the vehicle origin's position at S plus Gaussian noise (per axis, drawn from
// (seed, S) so it is reproducible), converted to latitude/longitude around the GeoOrigin
// (georeference.hpp); speed and true course from the trajectory. The sentence reaches the
// sensor sentence_latency_s after S, so packets run ahead of their fix as real ones do
// (sensor_clock.hpp). With GNSS disabled no receiver is attached: the sentence region is
// NUL and the PPS byte says absent, as in the real captures without GPS (a void 'V' sentence
// would tell a decoder no more: SensorClock rejects void fixes). Formats follow the real captures: the
// MRPT VLP-16 receiver's decimals for the VLP-16 and VLP-32C, the Garmin of the HDL-32E
// capture for the HDL-32E, whose PPS byte is unused (0). Simulating allocates nothing.
#pragma once

#include <cstdint>

#include "hal/common/time.hpp"
#include "hal/sim/lidar_options.hpp"
#include "hal/sim/trajectory.hpp"
#include "hal/velodyne/nmea.hpp"
#include "hal/velodyne/position_packet_encoder.hpp"

namespace flat2d::hal::sim {

class PositionPacketSimulator {
 public:
  // `trajectory` must outlive the simulator; `options` must be valid.
  PositionPacketSimulator(const Trajectory& trajectory, const LidarOptions& options,
                          std::uint64_t seed);

  // Drive time at which the sensor assembles position packet j: (j + 1/2) periods.
  TimeNs AssemblyTimeNs(std::uint64_t j) const;

  // Position packet j, any j in any order.
  void Simulate(std::uint64_t j, velodyne::PositionPacketBytes& out) const;

  // The receiver's report for the PPS second that starts at Unix second `unix_second`
  // (void, with time but no position, when GNSS is disabled).
  velodyne::RmcFix FixOfSecond(std::int64_t unix_second) const;

 private:
  const Trajectory* trajectory_;
  LidarOptions options_;
  std::uint64_t seed_;
  TimeNs period_ns_;
  TimeNs sentence_latency_ns_;
  velodyne::RmcFormat format_;
  velodyne::PpsStatus pps_status_;
};

}  // namespace flat2d::hal::sim
