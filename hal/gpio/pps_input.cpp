#include "hal/gpio/pps_input.hpp"

namespace flat2d::hal::gpio {

Result<PpsPollResult> PpsInput::Poll(TimeNs timeout_ns) {
  PpsPollResult result;
  Result<bool> ready = source_->Wait(timeout_ns);
  if (!ready.ok()) return ready.error();
  if (!*ready) return result;
  // Keep reading while reads come back full: more may be queued than one buffer holds.
  for (;;) {
    Result<std::size_t> read = source_->Read(buffer_);
    if (!read.ok()) return read.error();
    for (std::size_t i = 0; i < *read; ++i) Feed(buffer_[i], result);
    if (*read < buffer_.size()) break;
  }
  return result;
}

void PpsInput::Feed(const EdgeEvent& event, PpsPollResult& result) {
  ++result.events;
  if (next_sequence_ && event.sequence > *next_sequence_) {
    result.dropped_events += event.sequence - *next_sequence_;
  }
  next_sequence_ = event.sequence + 1;
  if (event.edge != pulse_edge_) return;
  ++result.pulses;
  if (clock_->AddPulse(event.time_ns).verdict == PulseVerdict::kSpurious) ++result.spurious;
}

}  // namespace flat2d::hal::gpio
