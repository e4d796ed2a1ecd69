// Verification of the checksums vehicle makers put in their CAN frames, so a decoder can
// count and drop corrupted or spoofed frames before their values reach odometry.
//
// Algorithms as opendbc implements them for its packer and parser (commaai/opendbc,
// opendbc/can/common.cc: toyota_checksum, honda_checksum; dbc.cc get_checksum gives the
// layouts), confirmed here on real logs (tests/hal/can/can_real_data_test.cpp):
//  - Toyota: last byte = (sum of the id's bytes + payload length + sum of all payload
//    bytes but the last) & 0xFF. The DBC names it CHECKSUM, 8 bits, the whole last byte.
//  - Honda: low nibble of the last byte = (8 - (sum of the id's nibbles + every payload
//    nibble except that checksum nibble)) & 0xF, plus 3 for a 29-bit id. The DBC names it
//    CHECKSUM, 4 bits, the low nibble of the last byte (Motorola start bit 8 * dlc - 5).
// Selection: DetectChecksum recognises those layouts in a DBC message. A layout does not
// name its maker (Chrysler's different 8-bit checksum has Toyota's layout; opendbc picks by
// DBC file name), so configuration can override per message, including kNone, and can
// name a kind for messages whose DBC entry lacks a CHECKSUM signal (the RAV4's 0x24/0x25).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hal/can/can_frame.hpp"
#include "hal/can/dbc.hpp"

namespace flat2d::hal::can {

enum class ChecksumKind : std::uint8_t { kNone, kToyota, kHonda };

std::string_view ChecksumKindName(ChecksumKind kind);  // "none", "toyota", "honda"
std::optional<ChecksumKind> ParseChecksumKind(std::string_view name);

// The value the last byte (Toyota) or its low nibble (Honda) must hold. The payload
// includes the checksum byte; it must not be empty.
std::uint8_t ToyotaChecksum(std::uint32_t id, std::span<const std::uint8_t> payload);
std::uint8_t HondaChecksum(std::uint32_t id, bool extended, std::span<const std::uint8_t> payload);

// True when the frame carries a valid checksum of `kind` (always for kNone); an empty
// payload fails every kind but kNone.
bool VerifyChecksum(ChecksumKind kind, const CanFrame& frame);

// The kind whose layout the message's CHECKSUM signal has, else kNone.
ChecksumKind DetectChecksum(const DbcMessage& message);

struct ChecksumOverride {
  std::string message;  // DBC message name
  ChecksumKind kind = ChecksumKind::kNone;
};

struct ChecksumOptions {
  bool detect = true;  // DetectChecksum for messages without an override
  std::vector<ChecksumOverride> overrides;
};

// The checksum to verify on `message` under `options`.
ChecksumKind SelectChecksum(const DbcMessage& message, const ChecksumOptions& options);

}  // namespace flat2d::hal::can
