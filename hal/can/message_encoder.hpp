// Building the CAN frames of one DBC message from physical signal values, for the
// simulator (issue 5, item 4) that emits the frames of a DBC it ships.
//
// Steps: Create finds the message by name, compiles every signal (signal_encoder.hpp),
// picks the checksum (explicit ChecksumKind, else DetectChecksum: checksum.hpp, after
// opendbc's packer) and the rolling counter signal, and records which payload bits the
// DBC defines. Set writes one signal into the held payload (a multiplexed signal also
// writes its switch's value); values persist until Clear, as a transmitting ECU keeps its
// last value. Build copies the payload into a CanFrame with the DBC's id, id format and
// length, writes and advances the counter (modulo 2^length), then fills the checksum last
// because it covers every other bit: Toyota the whole last byte, Honda its low nibble.
// Errors (unknown message or signal, NaN, clamping) are values and counters, never crashes;
// every buffer is sized in Create (bound: the message's signals) and Set/Build allocate
// nothing.
#pragma once

#include <array>
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
#include "hal/can/signal_encoder.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::can {

struct MessageEncoderOptions {
  // Checksum to fill; nullopt = DetectChecksum on the DBC message. An explicit kind serves
  // messages whose DBC entry lacks a CHECKSUM signal (the RAV4's 0x24/0x25).
  std::optional<ChecksumKind> checksum;
  // Rolling counter advanced by Build when the message has a signal of this name; empty
  // disables it (the caller then sets the counter like any other signal).
  std::string counter_signal = "COUNTER";
};

struct MessageEncoderStats {
  std::uint64_t frames = 0;          // Build calls
  std::uint64_t sets = 0;            // Set calls
  std::uint64_t clamped = 0;         // kClamped
  std::uint64_t not_a_number = 0;    // kNotANumber
  std::uint64_t unknown_signal = 0;  // kUnknownSignal
};

class MessageEncoder {
 public:
  // Errors name the message and DBC: unknown message, a signal that does not compile, a
  // checksum on an empty message, a length that is no CAN FD length.
  static Result<MessageEncoder> Create(const Dbc& dbc, std::string_view message,
                                       const MessageEncoderOptions& options = {});
  static Result<MessageEncoder> Create(const DbcMessage& message, const MessageEncoderOptions& options = {});

  // Index of the first signal called `signal` (multiplexed signals may share a name).
  std::optional<std::size_t> IndexOf(std::string_view signal) const;
  EncodeStatus Set(std::size_t index, double physical);
  EncodeStatus Set(std::string_view signal, double physical);
  // Zeroes the held payload.
  void Clear() { payload_.fill(0); }
  // Replaces the held payload with `bytes` (the rest zeroed; beyond length() ignored): a
  // template for bits no signal defines, e.g. copied from a recorded frame.
  void SetPayload(std::span<const std::uint8_t> bytes);

  // The counter value the next Build writes.
  std::uint64_t counter() const { return counter_; }
  void set_counter(std::uint64_t next) { counter_ = next & counter_mask_; }
  bool has_counter() const { return counter_index_.has_value(); }

  // The frame of the held payload, with the counter written and advanced and the checksum.
  CanFrame Build(TimeNs time_ns = 0);

  // Per payload byte, the bits some signal or the checksum defines (the rest Build leaves 0).
  std::span<const std::uint8_t> defined_bits() const { return {defined_.data(), length_}; }
  std::uint32_t id() const { return id_; }
  bool extended() const { return extended_; }
  std::size_t length() const { return length_; }
  const std::string& name() const { return name_; }
  ChecksumKind checksum() const { return checksum_; }
  const MessageEncoderStats& stats() const { return stats_; }

 private:
  MessageEncoder() = default;
  Status AddSignals(const DbcMessage& message, const MessageEncoderOptions& options);
  void FillChecksum(std::span<std::uint8_t> payload) const;

  struct Entry {
    std::string name;
    CompiledSignalEncoder encoder;
    bool multiplexed = false;
    std::uint64_t multiplex_value = 0;
  };

  std::uint32_t id_ = 0;
  bool extended_ = false;
  std::size_t length_ = 0;
  std::string name_;
  ChecksumKind checksum_ = ChecksumKind::kNone;
  std::vector<Entry> entries_;
  std::optional<CompiledSignalEncoder> switch_;  // when the message is multiplexed
  std::optional<std::size_t> counter_index_;
  std::uint64_t counter_ = 0;
  std::uint64_t counter_mask_ = 0;
  std::array<std::uint8_t, kMaxFdDataBytes> payload_{};
  std::array<std::uint8_t, kMaxFdDataBytes> defined_{};
  MessageEncoderStats stats_;
};

}  // namespace flat2d::hal::can
