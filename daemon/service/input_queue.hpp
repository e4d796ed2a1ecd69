// The localization thread's inbox: one SPSC ring of Velodyne datagrams (from the LiDAR
// thread) and one of CAN frames (from the CAN thread), merged back into arrival order.
//
// Every item takes a number from one shared counter when it is pushed, and the consumer
// always takes the lower-numbered of the two heads, so frames and datagrams reach the
// pipeline in the order they arrived (localization_pipeline.hpp needs time order across
// both). A counting semaphore wakes the consumer; a full ring drops the new item and counts
// it (the producer must never wait: the kernel's buffer behind it would overflow instead).
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <semaphore>

#include "daemon/service/spsc_ring.hpp"
#include "hal/can/can_frame.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::daemon {

// The largest Velodyne datagram is a 1206-byte data packet; room for a jumbo sensor's too.
inline constexpr std::size_t kMaxQueuedDatagramBytes = 1500;

struct QueuedDatagram {
  std::uint64_t sequence = 0;
  TimeNs receive_time_ns = 0;
  hal::net::Ipv4Endpoint source;
  hal::net::Ipv4Endpoint destination;
  std::uint16_t length = 0;
  std::array<std::uint8_t, kMaxQueuedDatagramBytes> bytes{};

  hal::net::UdpDatagram view() const { return {receive_time_ns, source, destination, {bytes.data(), length}}; }
};

struct QueuedFrame {
  std::uint64_t sequence = 0;
  hal::can::CanFrame frame;
};

struct InputQueueStats {
  std::atomic<std::uint64_t> datagrams{0};         // pushed
  std::atomic<std::uint64_t> datagrams_dropped{0}; // ring full
  std::atomic<std::uint64_t> datagrams_too_long{0};
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> frames_dropped{0};
};

class InputQueue {
 public:
  InputQueue(std::size_t datagram_slots, std::size_t frame_slots)
      : datagrams_(datagram_slots), frames_(frame_slots) {}

  // Producers (one thread each). False: dropped, and counted.
  bool PushDatagram(const hal::net::UdpDatagram& datagram);
  bool PushFrame(const hal::can::CanFrame& frame);

  // Consumer: waits up to `timeout` for an item; then, if there is one, calls
  // on_datagram(const QueuedDatagram&) or on_frame(const hal::can::CanFrame&) for the
  // earlier-arrived head and returns true.
  template <typename OnDatagram, typename OnFrame>
  bool PopNext(std::chrono::milliseconds timeout, OnDatagram&& on_datagram, OnFrame&& on_frame) {
    if (!available_.try_acquire_for(timeout)) return false;
    const QueuedDatagram* datagram = datagrams_.Front();
    const QueuedFrame* frame = frames_.Front();
    if (datagram != nullptr && (frame == nullptr || datagram->sequence < frame->sequence)) {
      on_datagram(*datagram);
      datagrams_.Pop();
    } else if (frame != nullptr) {
      on_frame(frame->frame);
      frames_.Pop();
    }
    return true;
  }

  // Wakes a consumer waiting in PopNext without an item (it returns true, having called nothing).
  void Wake() { available_.release(); }

  // Producer: whether a datagram pushed now would find a slot (the ring has one producer, so
  // the answer holds until it pushes).
  bool HasDatagramRoom() const { return datagrams_.size() < datagrams_.capacity(); }

  const InputQueueStats& stats() const { return stats_; }
  std::size_t queued() const { return datagrams_.size() + frames_.size(); }

 private:
  SpscRing<QueuedDatagram> datagrams_;
  SpscRing<QueuedFrame> frames_;
  std::atomic<std::uint64_t> next_sequence_{0};
  std::counting_semaphore<> available_{0};
  InputQueueStats stats_;
};

}  // namespace flat2d::daemon
