// Decoder of the 512-byte position (telemetry, GPS) packet that Velodyne sensors send to UDP
// port 8308 (VLP-16 manual 63-9243, 9.3.3, Tables 9-3 and 9-4; VLP-32C manual 63-9325,
// 9.3.3, Table 9-3; HDL-32E manual 63-9113, Appendix B, "Positioning Packet", Fig. B3).
//
// Layout (payload offsets, all models): bytes 198-201 the sensor time in microseconds past
// the hour (little-endian uint32); byte 202 the PPS status (0 absent, 1 synchronizing,
// 2 locked, 3 error; the HDL-32E leaves it unused, so it reads 0); from byte 206 the last
// NMEA sentence the sensor received (normally $GPRMC; the VLP-32C may echo $GPGGA), ASCII,
// ended by CR/LF and padded with NUL bytes to the end of the payload. With no GPS attached
// the sentence is all NULs, which is not an error. Steps: check the size; read timestamp
// and PPS byte and reject out-of-range values; cut the sentence at its terminator and
// reject non-ASCII bytes; parse it if it is an RMC sentence (nmea.hpp).
//
// Other fields stay in `raw`, undecoded: the HDL-32E gyro/temperature/accelerometer words
// of Fig. B3 (bytes 14-37), and the board temperatures, ADC-calibration and thermal-status
// bytes 187-205 that newer VLP-32C firmware sends (Table 9-3).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/velodyne/nmea.hpp"
#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {

// VLP-16 manual Table 9-4 / VLP-32C manual Table 9-3.
enum class PpsStatus : std::uint8_t {
  kAbsent = 0,
  kSynchronizing = 1,
  kLocked = 2,
  kError = 3,
};

struct PositionPacket {
  std::uint32_t us_past_hour = 0;          // when the sensor assembled the packet
  PpsStatus pps_status = PpsStatus::kAbsent;
  std::uint16_t nmea_length = 0;           // sentence bytes at kPositionNmeaOffset of raw
  std::optional<RmcFix> rmc;               // set when the sentence is an RMC sentence
  std::array<std::uint8_t, kPositionPacketSize> raw{};  // the payload as received

  // The NMEA sentence without CR/LF; empty when no GPS is attached. A view into raw, so
  // decoding and copying a packet never touches the heap.
  std::string_view nmea_sentence() const {
    return {reinterpret_cast<const char*>(raw.data()) + kPositionNmeaOffset, nmea_length};
  }
};

// "absent", "synchronizing", "locked", "error".
std::string_view PpsStatusName(PpsStatus status);

// Decodes one UDP payload of exactly kPositionPacketSize bytes. A wrong size, a timestamp of
// an hour or more, an unknown PPS byte, a sentence that is not printable ASCII or has no
// terminator, and an RMC sentence that fails to parse (e.g. bad checksum) are Errors.
Result<PositionPacket> DecodePositionPacket(std::span<const std::uint8_t> payload);

}  // namespace flat2d::hal::velodyne
