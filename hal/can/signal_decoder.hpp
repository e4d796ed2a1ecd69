// Extraction of one DBC signal from a frame's bytes, compiled once so the per-frame path
// is a handful of shifts and allocates nothing.
//
// Bit numbering (Vector "DBC File Format Documentation" 01/2007, signal definitions; the
// same walk as opendbc's dbc.cc be_bits table): bit b is bit b % 8 (LSB = 0) of byte
// b / 8. Intel (@1) signals start at their LSB and run up through the bytes
// (little-endian). Motorola (@0) signals start at their MSB and run down the byte, then on
// to bit 7 of the next byte (the "sawtooth": 7, 6 .. 0, 15, 14 .. 8, 23 ...), so in the
// big-endian linear numbering lin(b) = 8 * (b / 8) + 7 - b % 8 the MSB sits at lin(start)
// and the LSB at lin(start) + length - 1. Steps: Compile walks the value's
// bits once and records, for each byte the signal touches, (byte, right shift, mask, left
// shift): at most 9 pieces for a 64-bit signal that starts mid-byte. Raw ORs the pieces;
// Physical sign-extends a signed value (two's complement in `length` bits) or reinterprets
// an IEEE one (SIG_VALTYPE_), then applies physical = raw * factor + offset.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "hal/can/dbc.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

// Payload bytes a signal needs: one past the highest byte it touches.
std::size_t SignalBytesNeeded(std::uint16_t start_bit, std::uint8_t length, bool little_endian);

class CompiledSignal {
 public:
  // Errors: a length outside 1..64, an IEEE type whose length is not 32/64, or bits past
  // the 64 bytes of a CAN FD frame.
  static Result<CompiledSignal> Compile(const DbcSignal& signal);

  std::size_t bytes_needed() const { return bytes_needed_; }
  std::uint8_t length() const { return length_; }

  // The signal's bits, zero-extended; nullopt when `payload` is shorter than bytes_needed()
  // (a data-dependent failure the caller counts).
  std::optional<std::uint64_t> Raw(std::span<const std::uint8_t> payload) const {
    if (payload.size() < bytes_needed_) return std::nullopt;
    std::uint64_t raw = 0;
    for (std::size_t i = 0; i < piece_count_; ++i) {
      const Piece& piece = pieces_[i];
      const std::uint64_t bits = (payload[piece.byte] >> piece.shift) & piece.mask;
      raw |= bits << piece.position;
    }
    return raw;
  }

  // Two's complement value of `raw` for signed signals; the raw bits otherwise.
  std::int64_t SignedRaw(std::uint64_t raw) const;
  // raw -> physical: sign extension or IEEE reinterpretation, then * factor + offset.
  double Physical(std::uint64_t raw) const;
  // Raw, then Physical.
  std::optional<double> Decode(std::span<const std::uint8_t> payload) const {
    const std::optional<std::uint64_t> raw = Raw(payload);
    if (!raw) return std::nullopt;
    return Physical(*raw);
  }

 private:
  // Value bits [position, position + popcount(mask)) come from (byte >> shift) & mask.
  struct Piece {
    std::uint8_t byte = 0;
    std::uint8_t shift = 0;
    std::uint8_t mask = 0;
    std::uint8_t position = 0;
  };
  // 64 bits starting at bit 7 of a byte touch 9 bytes.
  static constexpr std::size_t kMaxPieces = 9;

  std::array<Piece, kMaxPieces> pieces_{};
  std::size_t piece_count_ = 0;
  std::size_t bytes_needed_ = 0;
  std::uint8_t length_ = 0;
  bool is_signed_ = false;
  DbcValueType value_type_ = DbcValueType::kInteger;
  double factor_ = 1.0;
  double offset_ = 0.0;
};

}  // namespace flat2d::hal::can
