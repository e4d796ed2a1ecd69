#include "hal/can/checksum.hpp"

namespace flat2d::hal::can {
namespace {

constexpr std::uint32_t kMaxStandardIdValue = 0x7FF;

// True when `signal` covers exactly bits [low, low + width) of byte `byte`, in either
// byte order (within one byte both orders name the same bits).
bool CoversBits(const DbcSignal& signal, std::size_t byte, std::size_t low, std::size_t width) {
  if (signal.length != width) return false;
  const std::size_t first = 8 * byte + low;                // Intel: the LSB
  const std::size_t last = 8 * byte + low + width - 1;     // Motorola: the MSB
  return signal.start_bit == (signal.little_endian ? first : last);
}

}  // namespace

std::string_view ChecksumKindName(ChecksumKind kind) {
  switch (kind) {
    case ChecksumKind::kToyota:
      return "toyota";
    case ChecksumKind::kHonda:
      return "honda";
    case ChecksumKind::kNone:
      break;
  }
  return "none";
}

std::optional<ChecksumKind> ParseChecksumKind(std::string_view name) {
  for (ChecksumKind kind : {ChecksumKind::kNone, ChecksumKind::kToyota, ChecksumKind::kHonda}) {
    if (name == ChecksumKindName(kind)) return kind;
  }
  return std::nullopt;
}

std::uint8_t ToyotaChecksum(std::uint32_t id, std::span<const std::uint8_t> payload) {
  std::uint32_t sum = static_cast<std::uint32_t>(payload.size());
  for (std::uint32_t rest = id; rest != 0; rest >>= 8) sum += rest & 0xFF;
  for (std::size_t i = 0; i + 1 < payload.size(); ++i) sum += payload[i];
  return static_cast<std::uint8_t>(sum & 0xFF);
}

std::uint8_t HondaChecksum(std::uint32_t id, bool extended, std::span<const std::uint8_t> payload) {
  std::uint32_t sum = 0;
  for (std::uint32_t rest = id; rest != 0; rest >>= 4) sum += rest & 0xF;
  for (std::size_t i = 0; i < payload.size(); ++i) {
    // The last byte's low nibble is the checksum itself.
    const std::uint8_t byte = i + 1 == payload.size() ? payload[i] >> 4 : payload[i];
    sum += (byte & 0xFu) + (byte >> 4);
  }
  // opendbc treats ids above 0x7FF as extended; a flagged frame is extended by definition.
  const bool long_id = extended || id > kMaxStandardIdValue;
  const std::uint32_t checksum = 8u - sum + (long_id ? 3u : 0u);  // modular: only the nibble counts
  return static_cast<std::uint8_t>(checksum & 0xFu);
}

bool VerifyChecksum(ChecksumKind kind, const CanFrame& frame) {
  if (kind == ChecksumKind::kNone) return true;
  const std::span<const std::uint8_t> payload = frame.payload();
  if (payload.empty()) return false;
  if (kind == ChecksumKind::kToyota) return payload.back() == ToyotaChecksum(frame.id, payload);
  return (payload.back() & 0xFu) == HondaChecksum(frame.id, frame.extended, payload);
}

ChecksumKind DetectChecksum(const DbcMessage& message) {
  if (message.dlc == 0) return ChecksumKind::kNone;
  const std::size_t last_byte = message.dlc - 1u;
  bool toyota = false;
  bool honda = false;
  bool other = false;
  // Multiplexed messages may define CHECKSUM once per branch; all must agree.
  for (const DbcSignal& signal : message.signals) {
    if (signal.name != "CHECKSUM") continue;
    if (CoversBits(signal, last_byte, 0, 8)) {
      toyota = true;
    } else if (CoversBits(signal, last_byte, 0, 4)) {
      honda = true;
    } else {
      other = true;
    }
  }
  if (other || toyota == honda) return ChecksumKind::kNone;
  return toyota ? ChecksumKind::kToyota : ChecksumKind::kHonda;
}

ChecksumKind SelectChecksum(const DbcMessage& message, const ChecksumOptions& options) {
  for (const ChecksumOverride& entry : options.overrides) {
    if (entry.message == message.name) return entry.kind;
  }
  return options.detect ? DetectChecksum(message) : ChecksumKind::kNone;
}

}  // namespace flat2d::hal::can
