#include "hal/can/signal_encoder.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <string>

namespace flat2d::hal::can {
namespace {

std::uint64_t LowMask(std::uint8_t length) {
  return length >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << length) - 1;
}

// round(scaled) clamped to [0, 2^length - 1] or, signed, [-2^(length-1), 2^(length-1) - 1].
// The bounds are compared as exact powers of two, so 64-bit signals clamp correctly too.
RawEncoding ClampedInteger(double scaled, std::uint8_t length, bool is_signed) {
  const double rounded = std::round(scaled);  // half away from zero, as opendbc's packer
  const std::uint64_t mask = LowMask(length);
  if (!is_signed) {
    if (rounded < 0.0) return {0, EncodeStatus::kClamped};
    if (rounded >= std::ldexp(1.0, length)) return {mask, EncodeStatus::kClamped};
    return {static_cast<std::uint64_t>(rounded), EncodeStatus::kOk};
  }
  const double half = std::ldexp(1.0, length - 1);
  const std::uint64_t max = mask >> 1;
  if (rounded < -half) return {(max + 1) & mask, EncodeStatus::kClamped};
  if (rounded >= half) return {max, EncodeStatus::kClamped};
  // Two's complement in `length` bits; the conversion to unsigned is modular.
  return {static_cast<std::uint64_t>(static_cast<std::int64_t>(rounded)) & mask, EncodeStatus::kOk};
}

RawEncoding Float32Bits(double scaled) {
  constexpr double kMax = static_cast<double>(std::numeric_limits<float>::max());
  EncodeStatus status = EncodeStatus::kOk;
  if (std::fabs(scaled) > kMax && std::isfinite(scaled)) {
    scaled = std::copysign(kMax, scaled);
    status = EncodeStatus::kClamped;
  }
  return {std::bit_cast<std::uint32_t>(static_cast<float>(scaled)), status};
}

}  // namespace

Result<CompiledSignalEncoder> CompiledSignalEncoder::Compile(const DbcSignal& signal) {
  if (signal.factor == 0.0 || !std::isfinite(signal.factor) || !std::isfinite(signal.offset)) {
    return MakeError("signal " + signal.name + ": factor and offset must be finite and the factor non-zero");
  }
  Result<SignalLayout> layout = CompileSignalLayout(signal);
  if (!layout.ok()) return layout.error();
  return CompiledSignalEncoder(*layout);
}

RawEncoding CompiledSignalEncoder::ToRaw(double physical) const {
  const double scaled = (physical - layout_.offset) / layout_.factor;
  if (std::isnan(scaled)) return {0, EncodeStatus::kNotANumber};
  switch (layout_.value_type) {
    case DbcValueType::kFloat32:
      return Float32Bits(scaled);
    case DbcValueType::kFloat64:
      return {std::bit_cast<std::uint64_t>(scaled), EncodeStatus::kOk};
    case DbcValueType::kInteger:
      break;
  }
  return ClampedInteger(scaled, layout_.length, layout_.is_signed);
}

bool CompiledSignalEncoder::WriteRaw(std::span<std::uint8_t> payload, std::uint64_t raw) const {
  if (payload.size() < layout_.bytes_needed) return false;
  for (const SignalPiece& piece : layout_.used()) {
    const auto in_place = static_cast<std::uint8_t>(piece.mask << piece.shift);
    const auto bits = static_cast<std::uint8_t>(((raw >> piece.position) & piece.mask) << piece.shift);
    payload[piece.byte] = static_cast<std::uint8_t>((payload[piece.byte] & ~in_place) | bits);
  }
  return true;
}

EncodeStatus CompiledSignalEncoder::Encode(std::span<std::uint8_t> payload, double physical) const {
  if (payload.size() < layout_.bytes_needed) return EncodeStatus::kTooShort;
  const RawEncoding encoding = ToRaw(physical);
  if (!Written(encoding.status)) return encoding.status;
  WriteRaw(payload, encoding.raw);
  return encoding.status;
}

}  // namespace flat2d::hal::can
