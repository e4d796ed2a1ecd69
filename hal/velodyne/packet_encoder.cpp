#include "hal/velodyne/packet_encoder.hpp"

#include <cassert>
#include <cmath>
#include <string>

#include "hal/common/time.hpp"
#include "hal/velodyne/firing_timing.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr std::uint32_t kUsPerHour = static_cast<std::uint32_t>(kNsPerHour / kNsPerUs);
constexpr double kMaxRawDistance = 65535.0;

void PutU16(std::uint8_t* bytes, std::uint16_t value) {
  bytes[0] = static_cast<std::uint8_t>(value);
  bytes[1] = static_cast<std::uint8_t>(value >> 8);
}

void PutU32(std::uint8_t* bytes, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

Status Validate(const DataPacketContent& content) {
  if (!ReturnModeFromByte(static_cast<std::uint8_t>(content.mode))) {
    return MakeError("data packet: unknown return mode byte " +
                     std::to_string(static_cast<int>(content.mode)));
  }
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    if (content.block_azimuth_units[block] >= kAzimuthUnitsPerTurn) {
      return MakeError("data packet: block " + std::to_string(block) + " azimuth " +
                       std::to_string(content.block_azimuth_units[block]) +
                       " units, expected below 36000");
    }
  }
  if (content.us_past_hour >= kUsPerHour) {
    return MakeError("data packet: timestamp " + std::to_string(content.us_past_hour) +
                     " us is an hour or more");
  }
  return {};
}

}  // namespace

Result<DataPacketBytes> EncodeDataPacket(const DataPacketContent& content) {
  if (Status status = Validate(content); !status) return status.error();
  DataPacketBytes bytes{};
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    std::uint8_t* out = bytes.data() + block * kBlockSize;
    PutU16(out, kBlockFlag);
    PutU16(out + 2, content.block_azimuth_units[block]);
    out += kBlockHeaderSize;
    for (const ChannelRecord& record : content.records[block]) {
      PutU16(out, record.distance_units);
      out[2] = record.reflectivity;
      out += kChannelRecordSize;
    }
  }
  PutU32(bytes.data() + kTimestampOffset, content.us_past_hour);
  bytes[kReturnModeOffset] = static_cast<std::uint8_t>(content.mode);
  bytes[kProductIdOffset] = content.product_id;
  return bytes;
}

std::uint16_t RawDistance(double range_m, const LaserTable& table, int laser_id) {
  assert(laser_id >= 0 && laser_id < table.num_lasers);
  if (!std::isfinite(range_m) || table.distance_resolution_m <= 0.0) return 0;
  const double offset = table.lasers[static_cast<std::size_t>(laser_id)].distance_offset_m;
  const double units = std::round((range_m - offset) / table.distance_resolution_m);
  if (units < 1.0 || units > kMaxRawDistance) return 0;
  return static_cast<std::uint16_t>(units);
}

// Mirrors PacketDecoder::Decode: firing index, fan index (dual mode interleaves the two
// returns of a firing) and the channel's offset within its block from firing_timing.hpp.
FiringSchedule::FiringSchedule(Model model, ReturnMode mode) {
  const FiringTiming timing = TimingFor(model);
  const bool dual = mode == ReturnMode::kDual;
  const int blocks = static_cast<int>(kBlocksPerPacket);
  firings_per_packet_ = dual ? blocks / 2 : blocks;
  fans_per_block_ = timing.fans_per_block;
  block_period_us_ = timing.block_period_us;
  const int fan_stride = dual ? 2 : 1;
  for (int block = 0; block < static_cast<int>(kBlocksPerPacket); ++block) {
    const int firing = FiringOfBlock(block);
    const int first_fan = dual ? firing * fans_per_block_ * 2 + block % 2 : block * fans_per_block_;
    kinds_[static_cast<std::size_t>(block)] =
        (dual && block % 2 == 0) || mode == ReturnMode::kLast ? ReturnKind::kLast
                                                               : ReturnKind::kStrongest;
    for (int c = 0; c < static_cast<int>(kChannelsPerBlock); ++c) {
      ChannelFiring& f = firings_[static_cast<std::size_t>(block)][static_cast<std::size_t>(c)];
      f.time_offset_us = firing * timing.block_period_us +
                         timing.channel_offset_us[static_cast<std::size_t>(c)];
      f.fan = first_fan + (c / timing.lasers_per_fan) * fan_stride;
      f.laser_id = c % timing.lasers_per_fan;
    }
  }
}

}  // namespace flat2d::hal::velodyne
