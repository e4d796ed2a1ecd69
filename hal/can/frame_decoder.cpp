#include "hal/can/frame_decoder.hpp"

#include <algorithm>
#include <utility>

namespace flat2d::hal::can {
namespace {

constexpr std::uint32_t kExtendedKeyBit = 0x80000000u;

std::uint32_t KeyOf(std::uint32_t id, bool extended) { return id | (extended ? kExtendedKeyBit : 0u); }

// Refuses names the DBC does not know: a typo in the configuration must stop start-up.
Status CheckOverrides(const Dbc& dbc, const ChecksumOptions& checksums) {
  for (const ChecksumOverride& entry : checksums.overrides) {
    if (dbc.FindMessage(entry.message) == nullptr) {
      return MakeError("checksum override names message " + entry.message + ", which " + dbc.source +
                       " does not define");
    }
  }
  return Status::Ok();
}

// The DBC message of selection[slot], which must define the signal and not be selected
// before.
Result<const DbcMessage*> Resolve(const Dbc& dbc, std::span<const SignalSelection> selection, std::size_t slot) {
  const SignalSelection& wanted = selection[slot];
  const std::string label = "selected signal " + wanted.message + "." + wanted.signal + ": ";
  const DbcMessage* message = dbc.FindMessage(wanted.message);
  if (message == nullptr) return MakeError(label + dbc.source + " has no message " + wanted.message);
  if (message->FindSignal(wanted.signal) == nullptr) {
    return MakeError(label + "message " + wanted.message + " has no signal " + wanted.signal);
  }
  for (std::size_t earlier = 0; earlier < slot; ++earlier) {
    if (selection[earlier].message == wanted.message && selection[earlier].signal == wanted.signal) {
      return MakeError(label + "selected twice");
    }
  }
  return message;
}

}  // namespace

std::vector<SignalSelection> AllSignals(const Dbc& dbc) {
  std::vector<SignalSelection> selection;
  for (const DbcMessage& message : dbc.messages) {
    for (const DbcSignal& signal : message.signals) {
      if (message.FindSignal(signal.name) == &signal) selection.push_back({message.name, signal.name});
    }
  }
  return selection;
}

Result<MessageDecoder> MessageDecoder::Create(const DbcMessage& message, ChecksumKind checksum) {
  MessageDecoder decoder;
  decoder.id_ = message.id;
  decoder.extended_ = message.extended;
  decoder.name_ = message.name;
  decoder.checksum_ = checksum;
  if (const DbcSignal* mux = message.MultiplexSwitch()) {
    auto compiled = CompiledSignal::Compile(*mux);
    if (!compiled.ok()) return MakeError(message.name + ": " + compiled.error().message);
    decoder.switch_ = *compiled;
  }
  return decoder;
}

Status MessageDecoder::Add(const DbcSignal& signal, std::size_t slot) {
  auto compiled = CompiledSignal::Compile(signal);
  if (!compiled.ok()) return MakeError(name_ + ": " + compiled.error().message);
  const bool multiplexed = signal.multiplex == DbcMultiplex::kMultiplexed;
  reads_switch_ = reads_switch_ || multiplexed;
  entries_.push_back({*compiled, slot, multiplexed, signal.multiplex_value});
  return Status::Ok();
}

FrameStatus MessageDecoder::Decode(const CanFrame& frame, std::span<DecodedSignal> slots,
                                   std::span<std::size_t> updated, std::size_t& updated_count) const {
  const std::span<const std::uint8_t> payload = frame.payload();
  std::optional<std::uint64_t> switch_value;
  if (reads_switch_ && switch_) switch_value = switch_->Raw(payload);
  bool too_short = reads_switch_ && !switch_value;
  for (const Entry& entry : entries_) {
    if (entry.multiplexed && (!switch_value || *switch_value != entry.multiplex_value)) continue;
    const std::optional<std::uint64_t> raw = entry.signal.Raw(payload);
    if (!raw) {
      too_short = true;
      continue;
    }
    DecodedSignal& slot = slots[entry.slot];
    slot.raw = *raw;
    slot.value = entry.signal.Physical(*raw);
    slot.time_ns = frame.time_ns;
    ++slot.updates;
    updated[updated_count++] = entry.slot;
  }
  return too_short ? FrameStatus::kTooShort : FrameStatus::kDecoded;
}

Result<FrameDecoder> FrameDecoder::Create(const Dbc& dbc, std::span<const SignalSelection> selection,
                                          const ChecksumOptions& checksums) {
  if (Status status = CheckOverrides(dbc, checksums); !status.ok()) return status.error();
  FrameDecoder decoder;
  decoder.selection_.assign(selection.begin(), selection.end());
  for (std::size_t slot = 0; slot < selection.size(); ++slot) {
    const auto message = Resolve(dbc, selection, slot);
    if (!message.ok()) return message.error();
    const auto message_decoder = decoder.MessageFor(**message, checksums);
    if (!message_decoder.ok()) return message_decoder.error();
    // Every definition of the name: one per multiplexer value at most.
    for (const DbcSignal& signal : (*message)->signals) {
      if (signal.name != selection[slot].signal) continue;
      if (Status status = (*message_decoder)->Add(signal, slot); !status.ok()) return status.error();
    }
  }
  std::sort(decoder.messages_.begin(), decoder.messages_.end(), [](const auto& a, const auto& b) {
    return KeyOf(a.id(), a.extended()) < KeyOf(b.id(), b.extended());
  });
  for (const MessageDecoder& message : decoder.messages_) {
    decoder.keys_.push_back(KeyOf(message.id(), message.extended()));
  }
  decoder.slots_.resize(selection.size());
  decoder.updated_.resize(selection.size());
  return decoder;
}

Result<MessageDecoder*> FrameDecoder::MessageFor(const DbcMessage& message, const ChecksumOptions& checksums) {
  for (MessageDecoder& existing : messages_) {
    if (existing.id() == message.id && existing.extended() == message.extended) return &existing;
  }
  auto created = MessageDecoder::Create(message, SelectChecksum(message, checksums));
  if (!created.ok()) return created.error();
  messages_.push_back(std::move(*created));
  return &messages_.back();
}

FrameStatus FrameDecoder::Decode(const CanFrame& frame) {
  ++stats_.frames;
  updated_count_ = 0;
  const std::uint32_t key = KeyOf(frame.id, frame.extended);
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (frame.remote || frame.error || it == keys_.end() || *it != key) {
    ++stats_.ignored;
    return FrameStatus::kIgnored;
  }
  const MessageDecoder& message = messages_[static_cast<std::size_t>(it - keys_.begin())];
  if (message.checksum() != ChecksumKind::kNone) {
    ++stats_.checksum_checked;
    if (!VerifyChecksum(message.checksum(), frame)) {
      ++stats_.checksum_failures;
      return FrameStatus::kChecksumFailed;
    }
  }
  const FrameStatus status = message.Decode(frame, slots_, updated_, updated_count_);
  ++(status == FrameStatus::kTooShort ? stats_.too_short : stats_.decoded);
  return status;
}

std::optional<std::size_t> FrameDecoder::IndexOf(std::string_view message, std::string_view signal) const {
  for (std::size_t i = 0; i < selection_.size(); ++i) {
    if (selection_[i].message == message && selection_[i].signal == signal) return i;
  }
  return std::nullopt;
}

}  // namespace flat2d::hal::can
