#include "daemon/api/delimited_frames.hpp"

#include <algorithm>
#include <cstring>

namespace flat2d::wire {
namespace {

struct Prefix {
  FrameStatus status = FrameStatus::kNeedMore;
  std::uint64_t length = 0;
  std::size_t bytes = 0;
};

Prefix DecodePrefix(std::span<const std::uint8_t> data) {
  Prefix prefix;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (i == kMaxVarint32Bytes) {
      prefix.status = FrameStatus::kBadPrefix;
      return prefix;
    }
    prefix.length |= static_cast<std::uint64_t>(data[i] & 0x7F) << (7 * i);
    if ((data[i] & 0x80) == 0) {
      prefix.bytes = i + 1;
      prefix.status = prefix.length > 0xFFFFFFFFull ? FrameStatus::kBadPrefix : FrameStatus::kFrame;
      return prefix;
    }
  }
  if (data.size() >= kMaxVarint32Bytes) prefix.status = FrameStatus::kBadPrefix;
  return prefix;
}

}  // namespace

std::size_t VarintSize(std::uint32_t value) {
  std::size_t bytes = 1;
  while (value >= 0x80) {
    value >>= 7;
    ++bytes;
  }
  return bytes;
}

std::optional<std::size_t> AppendDelimited(const google::protobuf::MessageLite& message, std::size_t max_bytes,
                                           std::span<std::uint8_t> out, std::size_t used) {
  const std::size_t length = message.ByteSizeLong();
  if (length > max_bytes || length > 0xFFFFFFFFu) return std::nullopt;
  const std::size_t prefix = VarintSize(static_cast<std::uint32_t>(length));
  if (used > out.size() || out.size() - used < prefix + length) return std::nullopt;
  std::uint8_t* cursor = out.data() + used;
  auto value = static_cast<std::uint32_t>(length);
  while (value >= 0x80) {
    *cursor++ = static_cast<std::uint8_t>(value | 0x80);
    value >>= 7;
  }
  *cursor++ = static_cast<std::uint8_t>(value);
  if (!message.SerializeToArray(cursor, static_cast<int>(length))) return std::nullopt;
  return used + prefix + length;
}

FrameReader::FrameReader(std::size_t max_message_bytes)
    : max_message_bytes_(max_message_bytes), buffer_(max_message_bytes + kMaxVarint32Bytes) {}

std::span<std::uint8_t> FrameReader::WritableSpace() {
  Compact();
  return {buffer_.data() + end_, buffer_.size() - end_};
}

void FrameReader::Commit(std::size_t bytes) { end_ = std::min(buffer_.size(), end_ + bytes); }

FrameStatus FrameReader::Next() {
  frame_ = {};
  const std::span<const std::uint8_t> data(buffer_.data() + begin_, end_ - begin_);
  const Prefix prefix = DecodePrefix(data);
  if (prefix.status != FrameStatus::kFrame) return prefix.status;
  if (prefix.length > max_message_bytes_) return FrameStatus::kTooLarge;
  if (data.size() - prefix.bytes < prefix.length) return FrameStatus::kNeedMore;
  frame_ = data.subspan(prefix.bytes, static_cast<std::size_t>(prefix.length));
  begin_ += prefix.bytes + static_cast<std::size_t>(prefix.length);
  return FrameStatus::kFrame;
}

void FrameReader::Reset() {
  begin_ = end_ = 0;
  frame_ = {};
}

// Moves the unconsumed bytes to the front, so a frame of the maximum size always fits.
void FrameReader::Compact() {
  if (begin_ == 0) return;
  const std::size_t remaining = end_ - begin_;
  if (remaining > 0) std::memmove(buffer_.data(), buffer_.data() + begin_, remaining);
  begin_ = 0;
  end_ = remaining;
  frame_ = {};
}

}  // namespace flat2d::wire
