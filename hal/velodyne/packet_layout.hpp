// Byte layout of Velodyne UDP payloads (VLP-16 manual 63-9243 Rev E, 9.3.2-9.3.3;
// HDL-32E manual 63-9113 Rev M, 9.2; VLP-32C manual 63-9325 Rev C, 9.3.2-9.3.3).
//
// Data packet, 1206 bytes (port 2368): 12 blocks of 100 bytes, each the flag 0xFFEE
// (bytes FF EE), a little-endian azimuth in hundredths of a degree and 32 channel
// records (little-endian distance, reflectivity byte); then the timestamp
// (little-endian uint32, microseconds past the hour) and the two factory bytes.
// Position packet, 512 bytes (port 8308): timestamp at 198, PPS status at 202 and the
// last NMEA sentence received (normally $GPRMC) from 206.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace flat2d::hal::velodyne {

inline constexpr std::size_t kDataPacketSize = 1206;
inline constexpr std::size_t kBlocksPerPacket = 12;
inline constexpr std::size_t kChannelsPerBlock = 32;
inline constexpr std::size_t kBlockSize = 100;
inline constexpr std::size_t kChannelRecordSize = 3;
inline constexpr std::size_t kBlockHeaderSize = 4;  // flag + azimuth
inline constexpr std::size_t kTimestampOffset = 1200;
inline constexpr std::size_t kReturnModeOffset = 1204;
inline constexpr std::size_t kProductIdOffset = 1205;
inline constexpr std::uint16_t kBlockFlag = 0xEEFF;  // bytes FF EE read little-endian
inline constexpr std::uint16_t kAzimuthUnitsPerTurn = 36000;

inline constexpr std::size_t kPositionPacketSize = 512;
inline constexpr std::size_t kPositionTimestampOffset = 198;
inline constexpr std::size_t kPositionPpsStatusOffset = 202;
inline constexpr std::size_t kPositionNmeaOffset = 206;
inline constexpr std::size_t kPositionNmeaMaxLength = 512 - 206;

inline constexpr std::uint16_t kDefaultDataPort = 2368;
inline constexpr std::uint16_t kDefaultPositionPort = 8308;

inline std::uint16_t ReadU16(const std::uint8_t* bytes) {
  return static_cast<std::uint16_t>(bytes[0] | (bytes[1] << 8));
}

inline std::uint32_t ReadU32(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) |
         (static_cast<std::uint32_t>(bytes[3]) << 24);
}

}  // namespace flat2d::hal::velodyne
