#include "hal/velodyne/packet_encoder.hpp"

#include <cassert>
#include <cmath>
#include <string>

#include "hal/common/time.hpp"

namespace flat2d::hal::velodyne {
namespace {

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

}  // namespace flat2d::hal::velodyne
