#include "hal/can/signal_decoder.hpp"

#include <bit>

namespace flat2d::hal::can {

Result<CompiledSignal> CompiledSignal::Compile(const DbcSignal& signal) {
  Result<SignalLayout> layout = CompileSignalLayout(signal);
  if (!layout.ok()) return layout.error();
  return CompiledSignal(*layout);
}

std::int64_t CompiledSignal::SignedRaw(std::uint64_t raw) const {
  if (!layout_.is_signed || layout_.length == 64) return static_cast<std::int64_t>(raw);
  const std::uint64_t sign = std::uint64_t{1} << (layout_.length - 1);
  // (raw ^ sign) - sign: two's complement sign extension; the conversion is modular.
  return static_cast<std::int64_t>((raw ^ sign) - sign);
}

double CompiledSignal::Physical(std::uint64_t raw) const {
  double value = 0.0;
  switch (layout_.value_type) {
    case DbcValueType::kFloat32:
      value = static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(raw)));
      break;
    case DbcValueType::kFloat64:
      value = std::bit_cast<double>(raw);
      break;
    case DbcValueType::kInteger:
      value = layout_.is_signed ? static_cast<double>(SignedRaw(raw)) : static_cast<double>(raw);
      break;
  }
  return value * layout_.factor + layout_.offset;
}

}  // namespace flat2d::hal::can
