// Where a DBC signal's bits lie in a frame, computed once for both decoding
// (signal_decoder.hpp) and encoding (signal_encoder.hpp).
//
// Bit numbering (Vector "DBC File Format Documentation" 01/2007, signal definitions; the
// same walk as opendbc's dbc.cc be_bits table): bit b is bit b % 8 (LSB = 0) of byte
// b / 8. Intel (@1) signals start at their LSB and run up through the bytes
// (little-endian). Motorola (@0) signals start at their MSB and run down the byte, then on
// to bit 7 of the next byte (the "sawtooth": 7, 6 .. 0, 15, 14 .. 8, 23 ...), so in the
// big-endian linear numbering lin(b) = 8 * (b / 8) + 7 - b % 8 the MSB sits at lin(start)
// and the LSB at lin(start) + length - 1. The layout walks the value's bits once and
// records, for each byte the signal touches, a piece (byte, shift in the byte, mask,
// position in the value): at most 9 pieces for a 64-bit signal that starts mid-byte.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/can/dbc.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

// Payload bytes a signal needs: one past the highest byte it touches.
std::size_t SignalBytesNeeded(std::uint16_t start_bit, std::uint8_t length, bool little_endian);

struct SignalPiece {
  std::uint8_t byte = 0;      // payload byte
  std::uint8_t shift = 0;     // lowest bit of the piece within that byte
  std::uint8_t mask = 0;      // the piece's bits, right-aligned
  std::uint8_t position = 0;  // where the piece's lowest bit sits in the value
};

struct SignalLayout {
  static constexpr std::size_t kMaxPieces = 9;
  std::array<SignalPiece, kMaxPieces> pieces{};
  std::size_t piece_count = 0;
  std::size_t bytes_needed = 0;
  std::uint8_t length = 0;  // bits, 1..64
  bool is_signed = false;
  DbcValueType value_type = DbcValueType::kInteger;
  double factor = 1.0;
  double offset = 0.0;

  std::span<const SignalPiece> used() const { return {pieces.data(), piece_count}; }
};

// Errors name the signal: a length outside 1..64, an IEEE type of the wrong length, bits
// beyond the 64 bytes of a CAN FD frame.
Result<SignalLayout> CompileSignalLayout(const DbcSignal& signal);

}  // namespace flat2d::hal::can
