// Decoding of CAN frames into a fixed set of selected DBC signals, for the odometry hot
// path and for offline tools.
//
// Steps: Create resolves each selected (message, signal) name in the DBC, compiles the
// signal (signal_decoder.hpp) into a slot of a fixed array, groups the slots per message
// (MessageDecoder), picks each message's checksum (checksum.hpp) and sorts the messages
// by (id, extended) for binary search. Decode: find the frame's message; verify its
// checksum (a failure is counted and updates nothing, so callers drop the frame); when
// selected signals are multiplexed, read the switch and keep the signals of its value;
// extract the rest, counting frames too short for a signal (those slots keep their old
// value). A selected name that is defined once per multiplexer value (strym's TRACK_B_1
// COUNTER m0 / m1) binds all its definitions to one slot: a frame carries at most one.
// Every buffer is sized in Create (bound: the number of selected signals); Decode
// allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hal/can/can_frame.hpp"
#include "hal/can/checksum.hpp"
#include "hal/can/dbc.hpp"
#include "hal/can/signal_decoder.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::can {

struct SignalSelection {
  std::string message;  // DBC message name
  std::string signal;   // DBC signal name
};

// Every distinct (message, signal) of the DBC, in file order.
std::vector<SignalSelection> AllSignals(const Dbc& dbc);

enum class FrameStatus : std::uint8_t {
  kDecoded,         // a selected message; the signals it carries were updated
  kIgnored,         // no selected signal has this id, or a remote or error frame
  kChecksumFailed,  // the message's checksum did not verify; nothing was updated
  kTooShort,        // shorter than some selected signal needs; the others were updated
};

struct DecodedSignal {
  double value = 0.0;         // physical value, from the latest frame that carried it
  std::uint64_t raw = 0;      // its raw bits
  TimeNs time_ns = 0;         // that frame's time
  std::uint64_t updates = 0;  // frames that carried it; 0 = never seen
};

struct FrameDecoderStats {
  std::uint64_t frames = 0;             // Decode calls
  std::uint64_t decoded = 0;            // kDecoded
  std::uint64_t ignored = 0;            // kIgnored
  std::uint64_t checksum_checked = 0;   // frames whose message has a checksum
  std::uint64_t checksum_failures = 0;  // kChecksumFailed
  std::uint64_t too_short = 0;          // kTooShort
};

// The selected signals of one message.
class MessageDecoder {
 public:
  // Compiles the message's multiplexer switch, if it has one.
  static Result<MessageDecoder> Create(const DbcMessage& message, ChecksumKind checksum);

  // Binds `signal` (of this message) to `slot`; errors come from CompiledSignal::Compile.
  Status Add(const DbcSignal& signal, std::size_t slot);

  // Writes the frame's signals into slots[slot] and appends each slot it wrote to
  // `updated` from `updated_count` on (room: one entry per slot).
  FrameStatus Decode(const CanFrame& frame, std::span<DecodedSignal> slots, std::span<std::size_t> updated,
                     std::size_t& updated_count) const;

  std::uint32_t id() const { return id_; }
  bool extended() const { return extended_; }
  const std::string& name() const { return name_; }
  ChecksumKind checksum() const { return checksum_; }

 private:
  MessageDecoder() = default;

  struct Entry {
    CompiledSignal signal;
    std::size_t slot = 0;
    bool multiplexed = false;
    std::uint64_t multiplex_value = 0;
  };

  std::uint32_t id_ = 0;
  bool extended_ = false;
  std::string name_;
  ChecksumKind checksum_ = ChecksumKind::kNone;
  std::optional<CompiledSignal> switch_;  // when the message is multiplexed
  bool reads_switch_ = false;             // some selected signal is multiplexed
  std::vector<Entry> entries_;
};

class FrameDecoder {
 public:
  // Errors name the selection or override entry and the DBC: unknown message or signal,
  // a signal selected twice, a signal that does not compile.
  static Result<FrameDecoder> Create(const Dbc& dbc, std::span<const SignalSelection> selection,
                                     const ChecksumOptions& checksums = {});

  FrameStatus Decode(const CanFrame& frame);

  // One entry per selected signal, in selection order.
  std::span<const DecodedSignal> values() const { return slots_; }
  // Slots the last Decode wrote.
  std::span<const std::size_t> updated() const { return {updated_.data(), updated_count_}; }
  // Slot of a selected signal.
  std::optional<std::size_t> IndexOf(std::string_view message, std::string_view signal) const;
  std::span<const MessageDecoder> messages() const { return messages_; }
  const FrameDecoderStats& stats() const { return stats_; }

 private:
  FrameDecoder() = default;
  // The decoder of `message`, created on first use.
  Result<MessageDecoder*> MessageFor(const DbcMessage& message, const ChecksumOptions& checksums);

  std::vector<SignalSelection> selection_;
  std::vector<MessageDecoder> messages_;  // sorted by id, standard ids first
  std::vector<std::uint32_t> keys_;       // id, plus bit 31 for extended ids
  std::vector<DecodedSignal> slots_;
  std::vector<std::size_t> updated_;
  std::size_t updated_count_ = 0;
  FrameDecoderStats stats_;
};

}  // namespace flat2d::hal::can
