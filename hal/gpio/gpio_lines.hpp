// The GPIO HAL: an edge-event input line and a digital output line.
//
// The daemon's GPIO logic (PPS time discipline in pps_clock/pps_input, the "pose valid" line
// in pose_valid_output) talks only to these two small interfaces, so it is tested with fakes
// on machines without a gpiochip. libgpiod_lines.hpp implements both on real hardware
// through libgpiod v1. An input is used in two steps: Wait up to a timeout until events are
// pending, then Read them into a caller-owned buffer (no allocation per event).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"

namespace flat2d::hal::gpio {

// Logical edge: on a line requested active-low, a physical falling edge reads as kRising.
enum class Edge : std::uint8_t { kRising, kFalling };

// "rising", "falling".
constexpr std::string_view EdgeName(Edge edge) {
  return edge == Edge::kRising ? "rising" : "falling";
}

struct EdgeEvent {
  // When the edge happened: host CLOCK_REALTIME, ns since the Unix epoch (time.hpp), as
  // stamped by the kernel in the interrupt handler where the backend can (libgpiod does).
  TimeNs time_ns = 0;
  Edge edge = Edge::kRising;
  // 0, 1, 2... per opened line. A gap means events were lost between the source and us.
  std::uint64_t sequence = 0;
};

// The kernel's v1 line-event FIFO holds 16 events, and libgpiod v1 reads at most 16 per
// call; a buffer of this size empties the FIFO in one Read.
inline constexpr std::size_t kMaxEventsPerRead = 16;

class EdgeEventSource {
 public:
  virtual ~EdgeEventSource() = default;

  // Waits up to `timeout_ns` (0: just poll) for events to be pending. False on timeout and
  // when a signal interrupted the wait, so the caller's loop can check its stop flag.
  virtual Result<bool> Wait(TimeNs timeout_ns) = 0;

  // Moves up to out.size() pending events, oldest first, into `out`; returns how many.
  // Never blocks: with nothing pending it returns 0.
  virtual Result<std::size_t> Read(std::span<EdgeEvent> out) = 0;
};

class DigitalOutput {
 public:
  virtual ~DigitalOutput() = default;

  // Drives the line's logical value (true = active). On failure value() is unchanged.
  virtual Status Set(bool value) = 0;

  // The last value driven successfully (the initial value before any Set).
  virtual bool value() const = 0;
};

}  // namespace flat2d::hal::gpio
