#include "hal/can/signal_layout.hpp"

#include <string>

namespace flat2d::hal::can {
namespace {

constexpr std::size_t kMaxPayloadBytes = 64;  // CAN FD

// Big-endian linear index of DBC bit `bit`: 0 is bit 7 of byte 0, 8 is bit 7 of byte 1.
std::size_t MotorolaLinear(std::size_t bit) { return 8 * (bit / 8) + 7 - bit % 8; }

struct BitPlace {
  std::size_t byte = 0;
  std::size_t bit = 0;
};

// Byte and bit-in-byte of value bit k (0 = LSB).
BitPlace PlaceOf(const DbcSignal& signal, std::size_t k) {
  if (signal.little_endian) {
    const std::size_t position = signal.start_bit + k;
    return {position / 8, position % 8};
  }
  const std::size_t linear = MotorolaLinear(signal.start_bit) + (signal.length - 1 - k);
  return {linear / 8, 7 - linear % 8};
}

}  // namespace

std::size_t SignalBytesNeeded(std::uint16_t start_bit, std::uint8_t length, bool little_endian) {
  if (length == 0) return 0;
  if (little_endian) return (static_cast<std::size_t>(start_bit) + length - 1) / 8 + 1;
  return (MotorolaLinear(start_bit) + length - 1) / 8 + 1;
}

Result<SignalLayout> CompileSignalLayout(const DbcSignal& signal) {
  if (signal.length == 0 || signal.length > 64) {
    return MakeError("signal " + signal.name + ": length " + std::to_string(signal.length) +
                     " is outside 1..64 bits");
  }
  const bool ieee = signal.value_type != DbcValueType::kInteger;
  const std::uint8_t ieee_bits = signal.value_type == DbcValueType::kFloat32 ? 32 : 64;
  if (ieee && signal.length != ieee_bits) {
    return MakeError("signal " + signal.name + ": an IEEE value needs " + std::to_string(ieee_bits) + " bits");
  }
  SignalLayout layout;
  layout.bytes_needed = SignalBytesNeeded(signal.start_bit, signal.length, signal.little_endian);
  if (layout.bytes_needed > kMaxPayloadBytes) {
    return MakeError("signal " + signal.name + " reaches byte " + std::to_string(layout.bytes_needed - 1) +
                     ", past the 64 bytes of a CAN FD frame");
  }
  // Consecutive value bits in one byte are consecutive in-byte bits in both orders, so
  // one piece per byte suffices.
  for (std::size_t k = 0; k < signal.length; ++k) {
    const BitPlace place = PlaceOf(signal, k);
    SignalPiece* piece = layout.piece_count ? &layout.pieces[layout.piece_count - 1] : nullptr;
    if (piece == nullptr || piece->byte != place.byte) {
      piece = &layout.pieces[layout.piece_count++];
      piece->byte = static_cast<std::uint8_t>(place.byte);
      piece->shift = static_cast<std::uint8_t>(place.bit);
      piece->position = static_cast<std::uint8_t>(k);
    }
    piece->mask = static_cast<std::uint8_t>((piece->mask << 1) | 1u);
  }
  layout.length = signal.length;
  layout.is_signed = signal.is_signed;
  layout.value_type = signal.value_type;
  layout.factor = signal.factor;
  layout.offset = signal.offset;
  return layout;
}

}  // namespace flat2d::hal::can
