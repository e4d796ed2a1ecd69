#include "daemon/service/input_queue.hpp"

#include <algorithm>

namespace flat2d::daemon {

bool InputQueue::PushDatagram(const hal::net::UdpDatagram& datagram) {
  if (datagram.payload.size() > kMaxQueuedDatagramBytes) {
    stats_.datagrams_too_long.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  QueuedDatagram* slot = datagrams_.BeginPush();
  if (slot == nullptr) {
    stats_.datagrams_dropped.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  slot->sequence = next_sequence_.fetch_add(1, std::memory_order_relaxed);
  slot->receive_time_ns = datagram.receive_time_ns;
  slot->source = datagram.source;
  slot->destination = datagram.destination;
  slot->length = static_cast<std::uint16_t>(datagram.payload.size());
  std::copy(datagram.payload.begin(), datagram.payload.end(), slot->bytes.begin());
  datagrams_.CommitPush();
  stats_.datagrams.fetch_add(1, std::memory_order_relaxed);
  available_.release();
  return true;
}

bool InputQueue::PushFrame(const hal::can::CanFrame& frame) {
  QueuedFrame* slot = frames_.BeginPush();
  if (slot == nullptr) {
    stats_.frames_dropped.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  slot->sequence = next_sequence_.fetch_add(1, std::memory_order_relaxed);
  slot->frame = frame;
  frames_.CommitPush();
  stats_.frames.fetch_add(1, std::memory_order_relaxed);
  available_.release();
  return true;
}

}  // namespace flat2d::daemon
