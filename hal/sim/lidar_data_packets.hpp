// The simulated Velodyne's data packets: every channel record of packet k ray-cast into the
// scene from where the sensor was when that laser fired, then encoded byte-exactly.
//
// Steps per packet: (1) block azimuths from the rotation at each firing's time; (2) per
// block, the azimuth gap to the next firing and each channel's azimuth exactly as
// PacketDecoder will interpolate it (manuals 9.5), so the decoder reconstructs the very
// ray that was cast; (3) the sensor pose at the packet's first firing and one packet period
// later (Trajectory::At x vehicle_T_sensor), interpolated linearly per channel at its firing
// time (firing_schedule.hpp); (4) per ray: direction and origin from sin/cos tables and the
// laser's calibration, Scene::Cast, then dropout, Gaussian range noise and the range limits,
// drawn from a counter-based RNG keyed by (seed, packet, firing, channel pair); (5) the records
// (the dual-return mode repeats a firing's single return in both of its blocks) encoded by
// packet_encoder.hpp.
//
// Pose interpolation error: the interpolated pose differs from the trajectory's by at most
// a T^2 / 8 in position and alpha T^2 / 8 in rotation over a packet period T (0.55 ms for
// the HDL-32E, 1.33 ms for the VLP-16), i.e. below 1 um for a car (a < 10 m/s^2); where the
// trajectory's rates jump (ramp edges) the rotation error is up to |jump in rate| x T / 4.
// Timestamps: data packets carry whole microseconds (truncated), so a decoder's firing
// times are up to 1 us early. Simulating a packet allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "hal/common/time.hpp"
#include "hal/sim/lidar_options.hpp"
#include "hal/sim/scene.hpp"
#include "hal/sim/trajectory.hpp"
#include "hal/velodyne/firing_schedule.hpp"
#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/packet_encoder.hpp"

namespace flat2d::hal::sim {

class DataPacketSimulator {
 public:
  // `scene` and `trajectory` must outlive the simulator; `options` must be valid
  // (ValidateLidarOptions).
  DataPacketSimulator(const Scene& scene, const Trajectory& trajectory, const LidarOptions& options,
                      std::uint64_t seed);

  // Drive time of packet k's first firing (k x the packet period of the model and mode).
  TimeNs FirstFiringNs(std::uint64_t k) const { return static_cast<TimeNs>(k) * packet_period_ns_; }
  TimeNs packet_period_ns() const { return packet_period_ns_; }
  const velodyne::LaserTable& laser_table() const { return table_; }

  // Packet k, any k in any order (the result depends only on k, the inputs and the seed).
  void Simulate(std::uint64_t k, velodyne::DataPacketBytes& out);

 private:
  struct LaserGeometry {
    double cos_elevation, sin_elevation, vertical_offset_m, horizontal_offset_m;
  };
  struct ChannelConstants {
    float block_fraction;      // as PacketDecoder: channel offset / block period
    int azimuth_offset_units;  // -rot_correction in hundredths of a degree
  };
  struct SensorPose {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  };
  struct PacketMotion {  // world_T_sensor at the packet's start, and its change over the packet
    SensorPose start, delta;
  };

  SensorPose SensorPoseAt(TimeNs drive_time_ns) const;
  void UpdateMotion(std::uint64_t k);
  void FillBlockAzimuths(TimeNs first_firing_ns);
  std::array<int, velodyne::kBlocksPerPacket> DecoderAzimuthGaps() const;
  void SimulateBlock(std::uint64_t k, int block, int gap_units, TimeNs packet_start_ns);
  void MeasureRanges(std::uint64_t k, int block,
                     const std::array<double, velodyne::kChannelsPerBlock>& ranges);
  std::optional<SurfaceHit> CastRay(int block, int channel, int azimuth_units,
                                    TimeNs packet_start_ns) const;

  const Scene* scene_;
  const Trajectory* trajectory_;
  LidarOptions options_;
  std::uint64_t seed_;
  velodyne::LaserTable table_;
  velodyne::FiringTiming timing_;
  velodyne::FiringSchedule schedule_;
  TimeNs packet_period_ns_;
  TimeNs block_period_ns_;
  std::array<LaserGeometry, velodyne::kMaxLasers> lasers_{};
  std::array<ChannelConstants, velodyne::kChannelsPerBlock> channels_{};
  std::vector<double> cos_table_, sin_table_;  // by azimuth in hundredths of a degree
  double world_time_offset_s_;

  velodyne::DataPacketContent content_;
  PacketMotion motion_;
  std::uint64_t motion_packet_ = ~std::uint64_t{0};  // packet whose motion_ is computed
  SensorPose next_start_;                            // pose at the end of motion_packet_
};

}  // namespace flat2d::hal::sim
