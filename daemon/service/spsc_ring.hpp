// A single-producer single-consumer ring of preallocated slots (DESIGN.md "Threads"): the
// hand-off from a source thread to the localization thread without locks or allocation.
//
// The producer fills the slot BeginPush gives and publishes it with CommitPush; the
// consumer reads Front and releases it with Pop. Head and tail are only ever advanced by
// their own side, with release/acquire ordering, so a slot is never read while written.
#pragma once

#include <atomic>
#include <cstddef>
#include <new>
#include <vector>

namespace flat2d::daemon {

template <typename T>
class SpscRing {
 public:
  explicit SpscRing(std::size_t capacity) : slots_(capacity) {}

  // Producer: the slot to fill, or nullptr when the ring is full.
  T* BeginPush() {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= slots_.size()) return nullptr;
    return &slots_[head % slots_.size()];
  }
  void CommitPush() { head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  // Consumer: the oldest filled slot, or nullptr when the ring is empty.
  const T* Front() const {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return nullptr;
    return &slots_[tail % slots_.size()];
  }
  void Pop() { tail_.store(tail_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  std::size_t capacity() const { return slots_.size(); }
  std::size_t size() const { return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire); }

 private:
  static constexpr std::size_t kCacheLine = 64;
  std::vector<T> slots_;
  alignas(kCacheLine) std::atomic<std::size_t> head_{0};  // next slot to fill
  alignas(kCacheLine) std::atomic<std::size_t> tail_{0};  // next slot to read
};

}  // namespace flat2d::daemon
