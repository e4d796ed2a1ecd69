#include "hal/can/message_encoder.hpp"

#include <algorithm>
#include <string>

namespace flat2d::hal::can {
namespace {

std::uint64_t LowMask(std::uint8_t length) {
  return length >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << length) - 1;
}

// The checksum's own bits in the last byte: Toyota all of it, Honda the low nibble.
std::uint8_t ChecksumBits(ChecksumKind kind) {
  switch (kind) {
    case ChecksumKind::kToyota:
      return 0xFF;
    case ChecksumKind::kHonda:
      return 0x0F;
    case ChecksumKind::kNone:
      break;
  }
  return 0;
}

}  // namespace

Result<MessageEncoder> MessageEncoder::Create(const Dbc& dbc, std::string_view message,
                                              const MessageEncoderOptions& options) {
  const DbcMessage* found = dbc.FindMessage(message);
  if (found == nullptr) {
    return MakeError("message " + std::string(message) + " is not defined in " + dbc.source);
  }
  return Create(*found, options);
}

Result<MessageEncoder> MessageEncoder::Create(const DbcMessage& message, const MessageEncoderOptions& options) {
  if (message.dlc > kMaxFdDataBytes || !IsValidFdLength(message.dlc)) {
    return MakeError("message " + message.name + ": length " + std::to_string(message.dlc) +
                     " is not a CAN FD length");
  }
  MessageEncoder encoder;
  encoder.id_ = message.id;
  encoder.extended_ = message.extended;
  encoder.length_ = message.dlc;
  encoder.name_ = message.name;
  encoder.checksum_ = options.checksum.value_or(DetectChecksum(message));
  if (encoder.checksum_ != ChecksumKind::kNone && message.dlc == 0) {
    return MakeError("message " + message.name + ": a " + std::string(ChecksumKindName(encoder.checksum_)) +
                     " checksum needs at least one byte");
  }
  if (Status added = encoder.AddSignals(message, options); !added) return added.error();
  if (encoder.checksum_ != ChecksumKind::kNone) encoder.defined_[encoder.length_ - 1] |= ChecksumBits(encoder.checksum_);
  return encoder;
}

Status MessageEncoder::AddSignals(const DbcMessage& message, const MessageEncoderOptions& options) {
  if (const DbcSignal* multiplexer = message.MultiplexSwitch(); multiplexer != nullptr) {
    Result<CompiledSignalEncoder> compiled = CompiledSignalEncoder::Compile(*multiplexer);
    if (!compiled) return MakeError("message " + message.name + ": " + compiled.error().message);
    switch_ = *compiled;
  }
  entries_.reserve(message.signals.size());
  for (const DbcSignal& signal : message.signals) {
    Result<CompiledSignalEncoder> compiled = CompiledSignalEncoder::Compile(signal);
    if (!compiled) return MakeError("message " + message.name + ": " + compiled.error().message);
    if (compiled->bytes_needed() > length_) {
      return MakeError("message " + message.name + ": signal " + signal.name + " does not fit its " +
                       std::to_string(length_) + " bytes");
    }
    // All-ones raw marks the signal's bits in the defined-bits map.
    compiled->WriteRaw(defined_, ~std::uint64_t{0});
    const bool multiplexed = signal.multiplex == DbcMultiplex::kMultiplexed;
    if (!options.counter_signal.empty() && signal.name == options.counter_signal && !counter_index_) {
      counter_index_ = entries_.size();
      counter_mask_ = LowMask(signal.length);
    }
    entries_.push_back({signal.name, *compiled, multiplexed, signal.multiplex_value});
  }
  return Status::Ok();
}

std::optional<std::size_t> MessageEncoder::IndexOf(std::string_view signal) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [signal](const Entry& entry) { return entry.name == signal; });
  if (it == entries_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - entries_.begin());
}

EncodeStatus MessageEncoder::Set(std::size_t index, double physical) {
  ++stats_.sets;
  if (index >= entries_.size()) {
    ++stats_.unknown_signal;
    return EncodeStatus::kUnknownSignal;
  }
  const Entry& entry = entries_[index];
  const std::span<std::uint8_t> payload(payload_.data(), length_);
  const EncodeStatus status = entry.encoder.Encode(payload, physical);
  if (status == EncodeStatus::kClamped) ++stats_.clamped;
  if (status == EncodeStatus::kNotANumber) ++stats_.not_a_number;
  // A multiplexed value only means something under its switch value.
  if (Written(status) && entry.multiplexed && switch_) switch_->WriteRaw(payload, entry.multiplex_value);
  return status;
}

EncodeStatus MessageEncoder::Set(std::string_view signal, double physical) {
  const std::optional<std::size_t> index = IndexOf(signal);
  if (!index) {
    ++stats_.sets;
    ++stats_.unknown_signal;
    return EncodeStatus::kUnknownSignal;
  }
  return Set(*index, physical);
}

void MessageEncoder::SetPayload(std::span<const std::uint8_t> bytes) {
  payload_.fill(0);
  std::copy_n(bytes.begin(), std::min(bytes.size(), length_), payload_.begin());
}

CanFrame MessageEncoder::Build(TimeNs time_ns) {
  ++stats_.frames;
  const std::span<std::uint8_t> held(payload_.data(), length_);
  if (counter_index_) {
    entries_[*counter_index_].encoder.WriteRaw(held, counter_);
    counter_ = (counter_ + 1) & counter_mask_;
  }
  CanFrame frame;
  frame.time_ns = time_ns;
  frame.id = id_;
  frame.extended = extended_;
  frame.fd = length_ > kMaxClassicDataBytes;
  frame.length = static_cast<std::uint8_t>(length_);
  std::copy(held.begin(), held.end(), frame.data.begin());
  FillChecksum({frame.data.data(), length_});
  return frame;
}

void MessageEncoder::FillChecksum(std::span<std::uint8_t> payload) const {
  switch (checksum_) {
    case ChecksumKind::kToyota:
      payload.back() = ToyotaChecksum(id_, payload);
      break;
    case ChecksumKind::kHonda:
      payload.back() = static_cast<std::uint8_t>((payload.back() & 0xF0u) | HondaChecksum(id_, extended_, payload));
      break;
    case ChecksumKind::kNone:
      break;
  }
}

}  // namespace flat2d::hal::can
