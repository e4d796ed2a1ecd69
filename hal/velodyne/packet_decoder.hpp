// Decoder of Velodyne 1206-byte data packets into Cartesian vertical fans
// (VLP-16, HDL-32E, VLP-32C; strongest, last and dual return).
//
// Steps per packet: check size, block flags and factory bytes; per block find the
// azimuth gap to the next firing (the manuals' "precision azimuth calculation", 9.5),
// which also survives azimuth jumps inside a packet (FOV-limited sensors) by reusing the
// last plausible gap; per channel record interpolate its azimuth from its firing time,
// apply the laser's calibration and convert to xyz with precomputed sine tables. The
// decoder is configured with one laser table (model); choosing the model is the job of
// model_identifier.hpp. Decoding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "hal/velodyne/fan.hpp"
#include "hal/velodyne/firing_schedule.hpp"
#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

enum class PacketError : std::uint8_t {
  kNone,
  kWrongSize,
  kBadBlockFlag,
  kAzimuthOutOfRange,
  kUnknownReturnMode,
};
std::string_view PacketErrorName(PacketError error);

inline constexpr int kMaxFansPerPacket = 24;  // VLP-16: 12 blocks x 2 firing sequences

struct DecodedPacket {
  PacketError error = PacketError::kNone;
  std::uint32_t us_past_hour = 0;  // device timestamp of the first firing
  ReturnMode return_mode = ReturnMode::kStrongest;
  std::uint8_t product_id = 0;
  int num_fans = 0;
  int num_points = 0;  // channel records with non-zero distance
  // Fan stamps are nanoseconds after the packet timestamp; the caller adds the
  // packet's absolute time (see sensor_clock.hpp).
  std::array<Fan, kMaxFansPerPacket> fans;
};

class PacketDecoder {
 public:
  explicit PacketDecoder(const LaserTable& table);

  // Decodes into `out` (reused between calls). On error, out.error says why and
  // out.num_fans is 0.
  void Decode(std::span<const std::uint8_t> payload, DecodedPacket& out);

  const LaserTable& table() const { return table_; }

 private:
  struct ChannelConstants {
    int laser_id;
    int fan_in_block;          // VLP-16: 0 or 1; others 0
    float cos_elevation, sin_elevation;
    float distance_offset_m, vertical_offset_m, horizontal_offset_m;
    float block_fraction;      // channel_offset / block period: azimuth interpolation
    int azimuth_offset_units;  // -rot_correction in hundredths of a degree
    std::uint16_t time_offset_ns;  // after its fan's first firing
  };

  PacketError Validate(std::span<const std::uint8_t> payload) const;
  int AzimuthGapUnits(const std::uint8_t* payload, int block, int block_step);
  int DecodeBlock(const std::uint8_t* block, int gap_units, const std::array<Fan*, 2>& fans);
  void UpdateChannelAzimuths(int gap_units);

  LaserTable table_;
  FiringTiming timing_;
  std::array<FiringSchedule, 3> schedules_;  // by return mode: strongest, last, dual
  float distance_resolution_m_;
  std::array<ChannelConstants, 32> channels_{};
  std::vector<float> cos_table_, sin_table_;  // by azimuth in hundredths of a degree
  int max_gap_units_ = 0;   // larger gaps are jumps, not rotation (2x the 20 Hz gap)
  int last_gap_units_ = 0;  // last plausible block-to-block azimuth gap
  // Per channel: interpolation for `channel_azimuth_gap_` plus the laser's azimuth offset.
  // The gap rarely changes between blocks, so this is recomputed rarely.
  int channel_azimuth_gap_ = -1;
  std::array<int, 32> channel_azimuth_units_{};
};

}  // namespace flat2d::hal::velodyne
