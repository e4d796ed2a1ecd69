// Length-delimited protobuf messages on a byte stream, as protobuf's delimited streams
// (a base-128 varint byte count, then the message): the framing of the flat2dd API.
//
// FrameReader collects bytes as they arrive on a non-blocking socket into a buffer sized
// once (the largest message plus its prefix) and hands out whole frames; a length above the
// bound or a prefix longer than a 32-bit varint is an error the caller answers by closing,
// because the stream cannot be resynchronized after it. Writing appends prefix and message
// to a caller's fixed buffer, or says it does not fit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <google/protobuf/message_lite.h>

namespace flat2d::wire {

inline constexpr std::size_t kMaxVarint32Bytes = 5;

// Bytes of the varint that encodes `value`.
std::size_t VarintSize(std::uint32_t value);

// Appends the message with its prefix to out[used, capacity); returns the new `used`, or
// nullopt (and leaves `out` as it was) when it does not fit or is larger than max_bytes.
std::optional<std::size_t> AppendDelimited(const google::protobuf::MessageLite& message, std::size_t max_bytes,
                                           std::span<std::uint8_t> out, std::size_t used);

enum class FrameStatus : std::uint8_t {
  kFrame,      // frame() holds one message's bytes
  kNeedMore,   // no whole frame buffered yet
  kTooLarge,   // the announced length is above max_message_bytes: close the stream
  kBadPrefix,  // more than 5 prefix bytes, or a length above 2^32: close the stream
};

class FrameReader {
 public:
  explicit FrameReader(std::size_t max_message_bytes);

  // Where the next received bytes go (empty when the buffer is full, which can only
  // happen after kTooLarge), and how many landed there.
  std::span<std::uint8_t> WritableSpace();
  void Commit(std::size_t bytes);

  // The next whole frame, if one is buffered; call until kNeedMore. A frame stays valid
  // until the next call of Next, WritableSpace or Reset.
  FrameStatus Next();
  std::span<const std::uint8_t> frame() const { return frame_; }

  void Reset();
  std::size_t buffered() const { return end_ - begin_; }

 private:
  void Compact();

  std::size_t max_message_bytes_;
  std::vector<std::uint8_t> buffer_;  // max_message_bytes + kMaxVarint32Bytes, sized once
  std::size_t begin_ = 0;             // first unconsumed byte
  std::size_t end_ = 0;               // one past the last received byte
  std::span<const std::uint8_t> frame_;
};

}  // namespace flat2d::wire
