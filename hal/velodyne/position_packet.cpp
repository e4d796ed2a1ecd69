#include "hal/velodyne/position_packet.hpp"

#include <algorithm>
#include <string_view>

#include "hal/common/time.hpp"

namespace flat2d::hal::velodyne {
namespace {

// The sentence region from offset 206 to the end of the payload: the text up to CR, LF or
// NUL. The manual pads with NULs after CR/LF, so an all-NUL region means "no sentence".
Result<std::size_t> SentenceLength(std::span<const std::uint8_t> region) {
  const auto end = std::find_if(region.begin(), region.end(), [](std::uint8_t byte) {
    return byte == '\r' || byte == '\n' || byte == '\0';
  });
  const auto length = static_cast<std::size_t>(end - region.begin());
  if (end == region.end()) {
    return MakeError("position packet: NMEA sentence at offset " +
                     std::to_string(kPositionNmeaOffset) + " has no CR, LF or NUL terminator");
  }
  for (std::size_t i = 0; i < length; ++i) {
    if (region[i] < 0x20 || region[i] > 0x7E) {
      return MakeError("position packet: non-ASCII byte in NMEA sentence at offset " +
                       std::to_string(kPositionNmeaOffset + i));
    }
  }
  if (length > 0 && region[0] != '$') {
    return MakeError("position packet: NMEA sentence at offset " +
                     std::to_string(kPositionNmeaOffset) + " does not start with '$'");
  }
  return length;
}

}  // namespace

std::string_view PpsStatusName(PpsStatus status) {
  switch (status) {
    case PpsStatus::kAbsent: return "absent";
    case PpsStatus::kSynchronizing: return "synchronizing";
    case PpsStatus::kLocked: return "locked";
    case PpsStatus::kError: return "error";
  }
  return "unknown";
}

Result<PositionPacket> DecodePositionPacket(std::span<const std::uint8_t> payload) {
  if (payload.size() != kPositionPacketSize) {
    return MakeError("position packet: " + std::to_string(payload.size()) +
                     " bytes, expected " + std::to_string(kPositionPacketSize));
  }
  PositionPacket packet;
  std::copy(payload.begin(), payload.end(), packet.raw.begin());
  packet.us_past_hour = ReadU32(payload.data() + kPositionTimestampOffset);
  if (packet.us_past_hour >= kUsPerHour) {
    return MakeError("position packet: timestamp " + std::to_string(packet.us_past_hour) +
                     " us at offset " + std::to_string(kPositionTimestampOffset) +
                     " is an hour or more");
  }
  const std::uint8_t pps = payload[kPositionPpsStatusOffset];
  if (pps > static_cast<std::uint8_t>(PpsStatus::kError)) {
    return MakeError("position packet: PPS status " + std::to_string(pps) +
                     " at offset " +
                     std::to_string(kPositionPpsStatusOffset) + ", expected 0-3");
  }
  packet.pps_status = static_cast<PpsStatus>(pps);
  Result<std::size_t> length = SentenceLength(payload.subspan(kPositionNmeaOffset));
  if (!length) return length.error();
  packet.nmea_length = static_cast<std::uint16_t>(*length);
  if (IsRmcSentence(packet.nmea_sentence())) {
    Result<RmcFix> fix = ParseRmc(packet.nmea_sentence());
    if (!fix) return MakeError("position packet: " + fix.error().message);
    packet.rmc = *fix;
  }
  return packet;
}

}  // namespace flat2d::hal::velodyne
