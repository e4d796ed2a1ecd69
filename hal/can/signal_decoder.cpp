#include "hal/can/signal_decoder.hpp"

#include <bit>
#include <string>

namespace flat2d::hal::can {
namespace {

constexpr std::size_t kMaxPayloadBytes = 64;  // CAN FD

// Big-endian linear index of DBC bit `bit`: 0 is bit 7 of byte 0, 8 is bit 7 of byte 1.
std::size_t MotorolaLinear(std::size_t bit) { return 8 * (bit / 8) + 7 - bit % 8; }

// Byte and bit-in-byte of value bit k (0 = LSB).
struct BitPlace {
  std::size_t byte = 0;
  std::size_t bit = 0;
};

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

Result<CompiledSignal> CompiledSignal::Compile(const DbcSignal& signal) {
  if (signal.length == 0 || signal.length > 64) {
    return MakeError("signal " + signal.name + ": length " + std::to_string(signal.length) +
                     " is outside 1..64 bits");
  }
  const bool ieee = signal.value_type != DbcValueType::kInteger;
  const std::uint8_t ieee_bits = signal.value_type == DbcValueType::kFloat32 ? 32 : 64;
  if (ieee && signal.length != ieee_bits) {
    return MakeError("signal " + signal.name + ": an IEEE value needs " + std::to_string(ieee_bits) + " bits");
  }
  CompiledSignal compiled;
  compiled.bytes_needed_ = SignalBytesNeeded(signal.start_bit, signal.length, signal.little_endian);
  if (compiled.bytes_needed_ > kMaxPayloadBytes) {
    return MakeError("signal " + signal.name + " reaches byte " + std::to_string(compiled.bytes_needed_ - 1) +
                     ", past the 64 bytes of a CAN FD frame");
  }
  // Consecutive value bits in one byte are consecutive in-byte bits in both orders, so
  // one piece per byte suffices.
  for (std::size_t k = 0; k < signal.length; ++k) {
    const BitPlace place = PlaceOf(signal, k);
    Piece* piece = compiled.piece_count_ ? &compiled.pieces_[compiled.piece_count_ - 1] : nullptr;
    if (piece == nullptr || piece->byte != place.byte) {
      piece = &compiled.pieces_[compiled.piece_count_++];
      piece->byte = static_cast<std::uint8_t>(place.byte);
      piece->shift = static_cast<std::uint8_t>(place.bit);
      piece->position = static_cast<std::uint8_t>(k);
    }
    piece->mask = static_cast<std::uint8_t>((piece->mask << 1) | 1u);
  }
  compiled.length_ = signal.length;
  compiled.is_signed_ = signal.is_signed;
  compiled.value_type_ = signal.value_type;
  compiled.factor_ = signal.factor;
  compiled.offset_ = signal.offset;
  return compiled;
}

std::int64_t CompiledSignal::SignedRaw(std::uint64_t raw) const {
  if (!is_signed_ || length_ == 64) return static_cast<std::int64_t>(raw);
  const std::uint64_t sign = std::uint64_t{1} << (length_ - 1);
  // (raw ^ sign) - sign: two's complement sign extension; the conversion is modular.
  return static_cast<std::int64_t>((raw ^ sign) - sign);
}

double CompiledSignal::Physical(std::uint64_t raw) const {
  double value = 0.0;
  switch (value_type_) {
    case DbcValueType::kFloat32:
      value = static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(raw)));
      break;
    case DbcValueType::kFloat64:
      value = std::bit_cast<double>(raw);
      break;
    case DbcValueType::kInteger:
      value = is_signed_ ? static_cast<double>(SignedRaw(raw)) : static_cast<double>(raw);
      break;
  }
  return value * factor_ + offset_;
}

}  // namespace flat2d::hal::can
