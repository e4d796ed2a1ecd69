// NMEA 0183 RMC ("recommended minimum") sentence parser, for the GPS sentence a Velodyne
// sensor echoes in its position packets (VLP-16 manual 63-9243, 7.4.5 "NMEA Message
// Formats"; VLP-32C manual 63-9325, same section).
//
// Steps: strip the line ending; verify the checksum (XOR of the characters between '$' and
// '*', two hex digits) when the sentence carries one; split at commas; read the UTC time of
// day hhmmss(.sss), the status (A = valid, V = void), latitude ddmm.mmmm and longitude
// dddmm.mmmm with their hemispheres, speed over ground (knots), true course, the date
// ddmmyy (years 80-99 are 19xx, others 20xx; NMEA carries only two digits), the optional
// magnetic variation and the optional mode indicator of NMEA 2.3 (N = not valid). Any talker
// is accepted ($GPRMC, $GNRMC, $GLRMC, ...). A void sentence may leave time, date and
// position empty; a malformed field is an Error that names the field.
#pragma once

#include <optional>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::velodyne {

struct RmcFix {
  // UTC date and time of the fix as ns since the Unix epoch; meaningful when has_time.
  TimeNs utc_time_ns = 0;
  bool has_time = false;      // both the time and the date fields were given
  bool valid = false;         // status 'A' and mode (if any) not 'N'
  bool has_position = false;  // latitude and longitude were given
  double latitude_deg = 0.0;  // north positive
  double longitude_deg = 0.0; // east positive
  double speed_mps = 0.0;     // speed over ground
  double course_deg = 0.0;    // true course over ground; 0 when not given
  std::optional<double> magnetic_variation_deg;  // east positive
  char status = 'V';          // 'A' or 'V' as sent
  char mode = '\0';           // NMEA 2.3 mode indicator (A, D, E, N, ...); '\0' if absent
};

// True when `sentence` starts like an RMC sentence ("$xxRMC,"); says nothing of its validity.
bool IsRmcSentence(std::string_view sentence);

// Parses one RMC sentence, with or without a trailing CR/LF.
Result<RmcFix> ParseRmc(std::string_view sentence);

}  // namespace flat2d::hal::velodyne
