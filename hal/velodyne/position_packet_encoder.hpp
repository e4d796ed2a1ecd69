// Encoder of the 512-byte Velodyne position packet, the inverse of position_packet.hpp
// (VLP-16 manual 63-9243, 9.3.3, Tables 9-3 and 9-4; VLP-32C manual 63-9325, 9.3.3;
// HDL-32E manual 63-9113, Appendix B), with an NMEA RMC sentence writer that nmea.hpp
// reads back (NMEA 0183 RMC, VLP-16 manual 7.4.5).
//
// Steps: validate the timestamp (below one hour) and the fix; write the timestamp at 198
// (little-endian), the PPS status at 202 and, from 206, "$<talker>RMC,..." with its
// checksum (XOR of the characters between '$' and '*', two upper-case hex digits) and
// CR/LF; every other byte is 0, as the VLP-16 sends it (the HDL-32E gyro, temperature and
// accelerometer words and the VLP-32C status bytes are not written). Numbers are written
// with fixed decimals (RmcFormat) so that a receiver's own formatting can be reproduced
// byte for byte; the time of day is truncated, angles and speeds rounded. The fields of an
// RmcFix are written as nmea.hpp parses them: no time and date when !has_time, no position
// when !has_position, no magnetic variation when absent, no mode field when mode is '\0';
// `valid` is derived by the parser and ignored here. Encoding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "hal/common/error.hpp"
#include "hal/velodyne/nmea.hpp"
#include "hal/velodyne/packet_layout.hpp"
#include "hal/velodyne/position_packet.hpp"

namespace flat2d::hal::velodyne {

// Decimal places (and zero-padded integer digits) of each number of the sentence. The
// defaults are those of the GPS in the MRPT VLP-16 capture ("081802.00", "3649.7478558",
// "0.034", "212.5", "0.0"); the HDL-32E Garmin of the rust-lidar-utils capture writes
// "220243", "3708.5809", "028.8", "158.3", "013.8": time 0, minutes 4, and 3 integer digits.
struct RmcFormat {
  std::array<char, 2> talker = {'G', 'P'};  // "GP": $GPRMC
  int time_decimals = 2;        // hhmmss.ss, 0-9
  int minute_decimals = 7;      // ddmm.mmmmmmm and dddmm.mmmmmmm, 0-9
  int speed_decimals = 3;       // knots, 0-6
  int course_decimals = 1;      // degrees, 0-6
  int variation_decimals = 1;   // degrees, 0-6
  int speed_digits = 1;         // integer digits, zero-padded, 1-5
  int course_digits = 1;        // 1-3
  int variation_digits = 1;     // 1-3
};

struct PositionPacketContent {
  std::uint32_t us_past_hour = 0;
  PpsStatus pps_status = PpsStatus::kAbsent;
  std::optional<RmcFix> rmc;  // none: the sentence region is all NUL (no GPS attached)
  RmcFormat format;
};

using PositionPacketBytes = std::array<std::uint8_t, kPositionPacketSize>;

// The 512-byte payload, or an Error naming the invalid field (e.g. an active fix without
// time or position, latitude beyond 90 degrees, a date outside 1980-2079 that two-digit
// NMEA years cannot carry).
Result<PositionPacketBytes> EncodePositionPacket(const PositionPacketContent& content);

}  // namespace flat2d::hal::velodyne
