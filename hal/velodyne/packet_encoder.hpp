// Encoder of Velodyne 1206-byte data packets, the exact inverse of packet_decoder.hpp
// (VLP-16 manual 63-9243 Rev E, 9.3.2; HDL-32E manual 63-9113 Rev M, 9.2; VLP-32C manual
// 63-9325 Rev C, 9.3.2), for the simulator and for tests.
//
// The content is raw-level, as the sensor sends it: 12 block azimuths in hundredths of a
// degree, 12 x 32 channel records (distance in the laser table's resolution units,
// reflectivity), the timestamp in microseconds past the hour and the two factory bytes.
// Steps: validate (azimuth below 36000, known return mode, timestamp below one hour); write
// each block's flag FF EE, little-endian azimuth and records; write the timestamp and the
// factory bytes. RawDistance gives the simulator what the decoder assumes (the inverse of
// range = raw x resolution + dist_correction, manuals 9.2); where and when each record
// fires is firing_schedule.hpp's, which the decoder uses too.
// Encoding allocates nothing; failure is an Error, never a malformed packet.
#pragma once

#include <array>
#include <cstdint>

#include "hal/common/error.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "hal/velodyne/model.hpp"
#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {

struct ChannelRecord {
  std::uint16_t distance_units = 0;  // 0 = no return; else x LaserTable::distance_resolution_m
  std::uint8_t reflectivity = 0;
};

struct DataPacketContent {
  std::array<std::uint16_t, kBlocksPerPacket> block_azimuth_units{};  // [0, 36000)
  std::array<std::array<ChannelRecord, kChannelsPerBlock>, kBlocksPerPacket> records{};
  std::uint32_t us_past_hour = 0;  // device time of the packet's first firing
  ReturnMode mode = ReturnMode::kStrongest;
  std::uint8_t product_id = kProductIdVlp16;  // written as given (firmware may lie, model.hpp)
};

using DataPacketBytes = std::array<std::uint8_t, kDataPacketSize>;

// The 1206-byte payload, or an Error naming the invalid field.
Result<DataPacketBytes> EncodeDataPacket(const DataPacketContent& content);

// Raw distance units that the decoder turns back into `range_m` for laser `laser_id`
// (0 <= laser_id < table.num_lasers): round((range - dist_correction) / resolution). 0 (no
// return) for a non-finite range or one that rounds below 1 unit or above 65535 units.
std::uint16_t RawDistance(double range_m, const LaserTable& table, int laser_id);

}  // namespace flat2d::hal::velodyne
