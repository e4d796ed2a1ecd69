// The source threads (DESIGN.md "Threads": packet ingest, CAN): each reads one sensor and
// pushes into the localization thread's input queue. A live source never waits on it (a
// full ring drops and counts); a capture replay waits for room and loses nothing.
//
// LiDAR: live UDP (udp_receiver.hpp: recvmmsg, kernel receive times, SO_RCVBUF sized for a
// stall of the consumer) or a capture file replayed at its recorded pace times `rate`
// (slower while the consumer is behind).
// CAN: a SocketCAN interface (socketcan_source.hpp: kernel receive times). A candump log is
// not a thread of its own: it follows the LiDAR's clock inside the localization thread
// (can_log_follower.hpp). Each thread's heartbeat advances at least every 100 ms while it
// runs; a replay that reached its end says finished() and no longer needs to beat.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <stop_token>

#include "daemon/config/flat2dd_config.pb.h"
#include "daemon/service/input_queue.hpp"
#include "hal/can/socketcan_source.hpp"
#include "hal/common/error.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/net/udp_receiver.hpp"
#include "hal/velodyne/velodyne_stream.hpp"

namespace flat2d::daemon {

class SourceThread {
 public:
  virtual ~SourceThread() = default;
  virtual void Run(std::stop_token stop, InputQueue& queue) = 0;
  // Drops the source reported (kernel buffer overflow, truncation), beside the queue's own.
  virtual std::uint64_t source_drops() const = 0;
  std::uint64_t heartbeat() const { return heartbeat_.load(std::memory_order_relaxed); }
  bool finished() const { return finished_.load(std::memory_order_acquire); }

 protected:
  void Beat() { heartbeat_.fetch_add(1, std::memory_order_relaxed); }
  void Finish() { finished_.store(true, std::memory_order_release); }

 private:
  std::atomic<std::uint64_t> heartbeat_{0};
  std::atomic<bool> finished_{false};
};

// The stream's sensor ports for the source: a capture keeps the recorded 2368/8308, a live
// socket takes the configured ones.
hal::velodyne::VelodyneStreamOptions StreamOptionsFor(const LidarSource& config);

// Opens the configured LiDAR source (the socket is bound, or the file read, before start-up
// reports ready).
Result<std::unique_ptr<SourceThread>> OpenLidarSource(const LidarSource& config);

// The SocketCAN source; nullptr for a candump log (which follows the LiDAR instead).
Result<std::unique_ptr<SourceThread>> OpenCanSource(const CanSource& config);

}  // namespace flat2d::daemon
