// Feeds the edges of a PPS input line to the clock-offset estimator (pps_clock.hpp).
//
// One Poll: wait up to a timeout for edges on the line, read them into a fixed buffer, and
// hand each edge that marks a pulse (rising, unless the receiver's pulse is inverted) to the
// PpsClock; the other edge, when the line was requested for both, ends the pulse and is
// skipped. A gap in the events' sequence numbers means the source dropped edges: they are
// counted here, and their pulses show up as missed in the estimator.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/gpio/gpio_lines.hpp"
#include "hal/gpio/pps_clock.hpp"

namespace flat2d::hal::gpio {

struct PpsPollResult {
  std::size_t events = 0;            // edges read
  std::size_t pulses = 0;            // pulse edges given to the estimator
  std::size_t spurious = 0;          // of those, pulses the estimator rejected
  std::uint64_t dropped_events = 0;  // sequence numbers skipped by the source
};

class PpsInput {
 public:
  // `source` and `clock` must outlive the PpsInput.
  PpsInput(EdgeEventSource& source, PpsClock& clock, Edge pulse_edge = Edge::kRising)
      : source_(&source), clock_(&clock), pulse_edge_(pulse_edge) {}

  // Waits up to `timeout_ns` for edges and feeds every pending one. Allocates nothing.
  Result<PpsPollResult> Poll(TimeNs timeout_ns);

 private:
  void Feed(const EdgeEvent& event, PpsPollResult& result);

  EdgeEventSource* source_;
  PpsClock* clock_;
  Edge pulse_edge_;
  std::array<EdgeEvent, kMaxEventsPerRead> buffer_{};  // one read drains the kernel FIFO
  std::optional<std::uint64_t> next_sequence_;
};

}  // namespace flat2d::hal::gpio
