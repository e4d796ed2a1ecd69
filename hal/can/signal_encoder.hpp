// Writing one DBC signal into a frame's bytes: the inverse of signal_decoder.hpp, for the
// simulator that emits the CAN frames of a DBC it ships.
//
// Bit numbering (Vector "DBC File Format Documentation" 01/2007, signal definitions; the
// same walk as opendbc's dbc.cc be_bits table and signal_decoder.hpp): bit b is bit b % 8
// (LSB = 0) of byte b / 8. Intel (@1) signals start at their LSB and run up through the
// bytes; Motorola (@0) signals start at their MSB and run down the byte, then on to bit 7
// of the next byte (the sawtooth 7, 6 .. 0, 15, 14 .. 8, 23 ...), so with the big-endian
// linear numbering lin(b) = 8 * (b / 8) + 7 - b % 8 the LSB sits at lin(start) + length - 1.
// Steps: Compile walks the value's bits once into at most 9 (byte, shift, mask, position)
// pieces, as the decoder does. Encode turns a physical value into raw bits the way
// opendbc's packer does (raw = round((physical - offset) / factor), eq. "physical = raw *
// factor + offset" of the DBC format inverted), clamps it to what `length` bits hold
// (two's complement range for signed signals) and reports the clamp, or bit-casts an IEEE
// value (SIG_VALTYPE_); WriteRaw clears the signal's bits and ORs the pieces in, leaving
// every other bit of the payload untouched. Nothing allocates after Compile.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/can/dbc.hpp"
#include "hal/can/signal_layout.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

enum class EncodeStatus : std::uint8_t {
  kOk,
  kClamped,        // the value was outside the signal's bit range; its nearest end was written
  kNotANumber,     // NaN; nothing was written
  kTooShort,       // the payload is shorter than the signal needs; nothing was written
  kUnknownSignal,  // (MessageEncoder) no such signal; nothing was written
};

// True when the value was written (kOk or kClamped).
inline bool Written(EncodeStatus status) {
  return status == EncodeStatus::kOk || status == EncodeStatus::kClamped;
}

struct RawEncoding {
  std::uint64_t raw = 0;  // the signal's bits, zero-extended (two's complement in `length`)
  EncodeStatus status = EncodeStatus::kOk;  // kOk, kClamped or kNotANumber
};

class CompiledSignalEncoder {
 public:
  // Errors: a length outside 1..64, an IEEE type whose length is not 32/64, bits past the
  // 64 bytes of a CAN FD frame, or a zero or non-finite factor (no inverse).
  static Result<CompiledSignalEncoder> Compile(const DbcSignal& signal);
  CompiledSignalEncoder() = default;  // encodes nothing until assigned a compiled signal

  std::size_t bytes_needed() const { return layout_.bytes_needed; }
  std::uint8_t length() const { return layout_.length; }

  // physical -> raw bits: round((physical - offset) / factor), clamped; IEEE bit cast.
  RawEncoding ToRaw(double physical) const;
  // Writes the low `length` bits of `raw`; false (nothing written) when `payload` is
  // shorter than bytes_needed().
  bool WriteRaw(std::span<std::uint8_t> payload, std::uint64_t raw) const;
  // ToRaw, then WriteRaw.
  EncodeStatus Encode(std::span<std::uint8_t> payload, double physical) const;

 private:
  explicit CompiledSignalEncoder(const SignalLayout& layout) : layout_(layout) {}

  SignalLayout layout_;
};

}  // namespace flat2d::hal::can
