// Extraction of one DBC signal from a frame's bytes, compiled once so the per-frame path
// is a handful of shifts and allocates nothing.
//
// The bit layout (DBC bit numbering, Intel and Motorola) is signal_layout.hpp's. Raw ORs
// the layout's pieces; Physical sign-extends a signed value (two's complement in `length`
// bits) or reinterprets an IEEE one (SIG_VALTYPE_), then applies
// physical = raw * factor + offset.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "hal/can/dbc.hpp"
#include "hal/can/signal_layout.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

class CompiledSignal {
 public:
  // Errors: a length outside 1..64, an IEEE type whose length is not 32/64, or bits past
  // the 64 bytes of a CAN FD frame.
  static Result<CompiledSignal> Compile(const DbcSignal& signal);
  CompiledSignal() = default;  // decodes nothing until assigned a compiled signal

  std::size_t bytes_needed() const { return layout_.bytes_needed; }
  std::uint8_t length() const { return layout_.length; }

  // The signal's bits, zero-extended; nullopt when `payload` is shorter than bytes_needed()
  // (a data-dependent failure the caller counts).
  std::optional<std::uint64_t> Raw(std::span<const std::uint8_t> payload) const {
    if (payload.size() < layout_.bytes_needed) return std::nullopt;
    std::uint64_t raw = 0;
    for (const SignalPiece& piece : layout_.used()) {
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
  explicit CompiledSignal(const SignalLayout& layout) : layout_(layout) {}

  SignalLayout layout_;
};

}  // namespace flat2d::hal::can
