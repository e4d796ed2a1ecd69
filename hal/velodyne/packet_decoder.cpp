#include "hal/velodyne/packet_decoder.hpp"

#include <cmath>
#include <numbers>

#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr int kUnitsPerTurn = kAzimuthUnitsPerTurn;
constexpr double kUnitsToRad = 2.0 * std::numbers::pi / kUnitsPerTurn;
constexpr double kRadToUnits = 1.0 / kUnitsToRad;
// Fastest rotation any supported model allows (20 Hz), in azimuth units per microsecond.
constexpr double kMaxUnitsPerUs = 1200.0 / 60.0 * kUnitsPerTurn * 1e-6;
constexpr double kNominalUnitsPerUs = kMaxUnitsPerUs / 2.0;  // 10 Hz

int WrapUnits(int units) {
  if (units >= kUnitsPerTurn) return units - kUnitsPerTurn;
  if (units < 0) return units + kUnitsPerTurn;
  return units;
}

std::size_t ScheduleIndex(ReturnMode mode) {
  return static_cast<std::size_t>(static_cast<std::uint8_t>(mode) - static_cast<std::uint8_t>(ReturnMode::kStrongest));
}

int BlockAzimuth(const std::uint8_t* payload, int block) {
  return ReadU16(payload + static_cast<std::size_t>(block) * kBlockSize + 2);
}

}  // namespace

std::string_view PacketErrorName(PacketError error) {
  switch (error) {
    case PacketError::kNone: return "none";
    case PacketError::kWrongSize: return "wrong_size";
    case PacketError::kBadBlockFlag: return "bad_block_flag";
    case PacketError::kAzimuthOutOfRange: return "azimuth_out_of_range";
    case PacketError::kUnknownReturnMode: return "unknown_return_mode";
  }
  return "unknown";
}

PacketDecoder::PacketDecoder(const LaserTable& table)
    : table_(table),
      timing_(TimingFor(table.model)),
      schedules_{FiringSchedule(table.model, ReturnMode::kStrongest),
                 FiringSchedule(table.model, ReturnMode::kLast),
                 FiringSchedule(table.model, ReturnMode::kDual)},
      distance_resolution_m_(static_cast<float>(table.distance_resolution_m)),
      cos_table_(kUnitsPerTurn),
      sin_table_(kUnitsPerTurn) {
  for (int units = 0; units < kUnitsPerTurn; ++units) {
    const double angle = units * kUnitsToRad;
    cos_table_[static_cast<std::size_t>(units)] = static_cast<float>(std::cos(angle));
    sin_table_[static_cast<std::size_t>(units)] = static_cast<float>(std::sin(angle));
  }
  for (int c = 0; c < static_cast<int>(kChannelsPerBlock); ++c) {
    ChannelConstants& k = channels_[static_cast<std::size_t>(c)];
    k.laser_id = c % timing_.lasers_per_fan;
    k.fan_in_block = c / timing_.lasers_per_fan;
    const LaserCorrection& laser = table_.lasers[static_cast<std::size_t>(k.laser_id)];
    k.cos_elevation = static_cast<float>(std::cos(laser.elevation_rad));
    k.sin_elevation = static_cast<float>(std::sin(laser.elevation_rad));
    k.distance_offset_m = static_cast<float>(laser.distance_offset_m);
    k.vertical_offset_m = static_cast<float>(laser.vertical_offset_m);
    k.horizontal_offset_m = static_cast<float>(laser.horizontal_offset_m);
    const double offset_us = timing_.channel_offset_us[static_cast<std::size_t>(c)];
    k.block_fraction = static_cast<float>(offset_us / timing_.block_period_us);
    k.azimuth_offset_units = static_cast<int>(std::lround(-laser.rot_correction_rad * kRadToUnits));
    const double fan_start_us =
        timing_.channel_offset_us[static_cast<std::size_t>(k.fan_in_block * timing_.lasers_per_fan)];
    k.time_offset_ns = static_cast<std::uint16_t>(std::lround((offset_us - fan_start_us) * 1e3));
  }
  max_gap_units_ = static_cast<int>(std::ceil(2.0 * kMaxUnitsPerUs * timing_.block_period_us));
  last_gap_units_ = static_cast<int>(std::lround(kNominalUnitsPerUs * timing_.block_period_us));
}

PacketError PacketDecoder::Validate(std::span<const std::uint8_t> payload) const {
  if (payload.size() != kDataPacketSize) return PacketError::kWrongSize;
  if (!ReturnModeFromByte(payload[kReturnModeOffset])) return PacketError::kUnknownReturnMode;
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    const std::uint8_t* header = payload.data() + block * kBlockSize;
    if (ReadU16(header) != kBlockFlag) return PacketError::kBadBlockFlag;
    if (ReadU16(header + 2) >= kAzimuthUnitsPerTurn) return PacketError::kAzimuthOutOfRange;
  }
  return PacketError::kNone;
}

// Azimuth advance from this block's firing to the next firing (9.5 of the manuals). A
// jump (FOV limit, lost rotation) or the packet's last firing reuses the last gap.
int PacketDecoder::AzimuthGapUnits(const std::uint8_t* payload, int block, int block_step) {
  const int next = block + block_step;
  if (next >= static_cast<int>(kBlocksPerPacket)) return last_gap_units_;
  const int gap = WrapUnits(BlockAzimuth(payload, next) - BlockAzimuth(payload, block));
  if (gap > max_gap_units_) return last_gap_units_;
  last_gap_units_ = gap;
  return gap;
}

void PacketDecoder::Decode(std::span<const std::uint8_t> payload, DecodedPacket& out) {
  out.num_fans = 0;
  out.num_points = 0;
  out.error = Validate(payload);
  if (out.error != PacketError::kNone) return;

  const std::uint8_t* bytes = payload.data();
  out.us_past_hour = ReadU32(bytes + kTimestampOffset);
  out.return_mode = *ReturnModeFromByte(bytes[kReturnModeOffset]);
  out.product_id = bytes[kProductIdOffset];

  const FiringSchedule& schedule = schedules_[ScheduleIndex(out.return_mode)];
  const int block_step = out.return_mode == ReturnMode::kDual ? 2 : 1;
  const int fans_per_block = timing_.fans_per_block;
  for (int block = 0; block < static_cast<int>(kBlocksPerPacket); ++block) {
    const int gap = AzimuthGapUnits(bytes, block, block_step);
    const int azimuth = BlockAzimuth(bytes, block);
    std::array<Fan*, 2> fans{};
    for (int f = 0; f < fans_per_block; ++f) {
      const ChannelFiring& first = schedule.At(block, f * timing_.lasers_per_fan);
      Fan& fan = out.fans[static_cast<std::size_t>(first.fan)];
      fan.stamp_ns = std::llround(first.time_offset_us * 1e3);
      fan.azimuth_rad = static_cast<float>(
          WrapUnits(azimuth + (gap * f) / fans_per_block) * kUnitsToRad);
      fan.kind = schedule.KindOfBlock(block);
      fan.num_lasers = static_cast<std::uint8_t>(timing_.lasers_per_fan);
      fan.num_points = 0;
      fans[static_cast<std::size_t>(f)] = &fan;
    }
    out.num_points += DecodeBlock(bytes + static_cast<std::size_t>(block) * kBlockSize, gap, fans);
  }
  out.num_fans = static_cast<int>(kBlocksPerPacket) * fans_per_block;
}

// Equations of the manuals' 9.2 with the driver calibration's offsets; returns the
// number of channel records with a return.
void PacketDecoder::UpdateChannelAzimuths(int gap_units) {
  const float gap = static_cast<float>(gap_units);
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const ChannelConstants& k = channels_[c];
    channel_azimuth_units_[c] = static_cast<int>(gap * k.block_fraction + 0.5f) + k.azimuth_offset_units;
  }
  channel_azimuth_gap_ = gap_units;
}

int PacketDecoder::DecodeBlock(const std::uint8_t* block, int gap_units,
                               const std::array<Fan*, 2>& fans) {
  if (gap_units != channel_azimuth_gap_) UpdateChannelAzimuths(gap_units);
  const int block_azimuth = ReadU16(block + 2);
  const std::uint8_t* record = block + kBlockHeaderSize;
  int points = 0;
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const ChannelConstants& k = channels_[c];
    LaserReturn& r = fans[static_cast<std::size_t>(k.fan_in_block)]->returns[static_cast<std::size_t>(k.laser_id)];
    const int raw_distance = ReadU16(record);
    const int azimuth = WrapUnits(block_azimuth + channel_azimuth_units_[c]);
    r.azimuth_rad = static_cast<float>(azimuth * kUnitsToRad);
    r.time_offset_ns = k.time_offset_ns;
    r.intensity = record[2];
    record += kChannelRecordSize;
    if (raw_distance == 0) {  // zero distance: no return
      r.range_m = 0.0f;
      r.xyz.setZero();
      continue;
    }
    const float range = static_cast<float>(raw_distance) * distance_resolution_m_ + k.distance_offset_m;
    const float horizontal = range * k.cos_elevation - k.vertical_offset_m * k.sin_elevation;
    const float cos_azimuth = cos_table_[static_cast<std::size_t>(azimuth)];
    const float sin_azimuth = sin_table_[static_cast<std::size_t>(azimuth)];
    r.range_m = range;
    ++fans[static_cast<std::size_t>(k.fan_in_block)]->num_points;
    r.xyz = Eigen::Vector3f(horizontal * cos_azimuth + k.horizontal_offset_m * sin_azimuth,
                            -horizontal * sin_azimuth + k.horizontal_offset_m * cos_azimuth,
                            range * k.sin_elevation + k.vertical_offset_m * k.cos_elevation);
    ++points;
  }
  return points;
}

}  // namespace flat2d::hal::velodyne
