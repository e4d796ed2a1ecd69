#include "daemon/service/gpio_wiring.hpp"

#include <cstdio>

#include "hal/gpio/libgpiod_lines.hpp"

namespace flat2d::daemon {
namespace {

constexpr TimeNs kPpsPollNs = 250'000'000;  // the stop token is checked this often
constexpr double kNsToUs = 1e-3;

hal::gpio::LineAddress AddressOf(const GpioLine& line) {
  return hal::gpio::LineAddress{.chip = line.chip(), .offset = line.offset(), .name = line.name()};
}

api::v1::PpsState StateOf(hal::gpio::PpsStatus status) {
  switch (status) {
    case hal::gpio::PpsStatus::kNoPps: return api::v1::PPS_NO_PULSES;
    case hal::gpio::PpsStatus::kAcquiring: return api::v1::PPS_ACQUIRING;
    case hal::gpio::PpsStatus::kLocked: return api::v1::PPS_LOCKED;
    case hal::gpio::PpsStatus::kLost: return api::v1::PPS_LOST;
  }
  return api::v1::PPS_NOT_CONFIGURED;
}

Error Prefixed(std::string_view what, const Error& error) { return MakeError(std::string(what) + ": " + error.message); }

}  // namespace

hal::gpio::PoseValidOptions PoseValidOptionsFor(const PoseValidOutputConfig& config) {
  return hal::gpio::PoseValidOptions{
      .min_on_ms = config.min_on_ms(),
      .min_off_ms = config.min_off_ms(),
      .active_level = config.active_low() ? hal::gpio::ActiveLevel::kLow : hal::gpio::ActiveLevel::kHigh};
}

hal::gpio::PpsClockOptions PpsClockOptionsFor(const PpsInputConfig& config) {
  hal::gpio::PpsClockOptions options;
  options.window_pulses = static_cast<int>(config.window_pulses());
  options.lock_pulses = static_cast<int>(config.lock_pulses());
  return options;
}

// The libgpiod lines requested by Open, kept alive for the wiring that points at them.
struct GpioWiring::OwnedLines {
  std::optional<hal::gpio::LibgpiodOutput> pose_valid;
  std::optional<hal::gpio::LibgpiodEdgeInput> pps;
};

Result<std::unique_ptr<GpioWiring>> GpioWiring::Open(const GpioConfig& config) {
  auto owned = std::make_unique<OwnedLines>();
  if (config.has_pose_valid()) {
    const hal::gpio::PoseValidOptions options = PoseValidOptionsFor(config.pose_valid());
    auto line = hal::gpio::LibgpiodOutput::Open({.line = AddressOf(config.pose_valid().line()),
                                                 .initial_value = hal::gpio::PoseValidSafeValue(options),
                                                 .consumer = "flat2dd pose-valid"});
    if (!line.ok()) return Prefixed("gpio.pose_valid", line.error());
    owned->pose_valid.emplace(std::move(*line));
  }
  if (config.has_pps()) {
    const bool falling = config.pps().falling_edge();
    auto line = hal::gpio::LibgpiodEdgeInput::Open(
        {.line = AddressOf(config.pps().line()),
         .edges = falling ? hal::gpio::EdgeSelection::kFalling : hal::gpio::EdgeSelection::kRising,
         .active_low = false,
         .consumer = "flat2dd pps"});
    if (!line.ok()) return Prefixed("gpio.pps", line.error());
    owned->pps.emplace(std::move(*line));
  }
  auto wiring = Create(config, owned->pose_valid ? &*owned->pose_valid : nullptr, owned->pps ? &*owned->pps : nullptr);
  if (!wiring.ok()) return wiring.error();
  (*wiring)->owned_ = std::move(owned);
  return wiring;
}

Result<std::unique_ptr<GpioWiring>> GpioWiring::Create(const GpioConfig& config,
                                                       hal::gpio::DigitalOutput* pose_valid_line,
                                                       hal::gpio::EdgeEventSource* pps_source) {
  std::unique_ptr<GpioWiring> wiring(new GpioWiring());
  if (config.has_pose_valid() && pose_valid_line != nullptr) {
    auto output = hal::gpio::PoseValidOutput::Create(*pose_valid_line, PoseValidOptionsFor(config.pose_valid()));
    if (!output.ok()) return Prefixed("gpio.pose_valid", output.error());
    wiring->pose_valid_.emplace(std::move(*output));
  }
  if (config.has_pps() && pps_source != nullptr) {
    auto clock = hal::gpio::PpsClock::Create(PpsClockOptionsFor(config.pps()));
    if (!clock.ok()) return Prefixed("gpio.pps", clock.error());
    wiring->pps_clock_.emplace(std::move(*clock));
    wiring->pps_source_ = pps_source;
    // The pulse edge is the requested one; for a falling-edge request that is kFalling.
    wiring->pps_input_.emplace(*pps_source, *wiring->pps_clock_,
                               config.pps().falling_edge() ? hal::gpio::Edge::kFalling : hal::gpio::Edge::kRising);
  }
  return wiring;
}

GpioWiring::~GpioWiring() { Stop(); }

void GpioWiring::UpdatePoseValid(bool pose_valid, TimeNs now_ns) {
  const std::lock_guard lock(output_mutex_);
  // A failed write is counted by the output and retried on the next tick.
  if (pose_valid_) (void)pose_valid_->Update(pose_valid, now_ns);
}

void GpioWiring::Stop() {
  const std::lock_guard lock(output_mutex_);
  if (pose_valid_ && !pose_valid_->stopped()) (void)pose_valid_->Stop();
}

void GpioWiring::RunPps(std::stop_token stop) {
  bool reported = false;
  while (!stop.stop_requested()) {
    pps_heartbeat_.fetch_add(1, std::memory_order_relaxed);
    if (Status polled = PollPps(kPpsPollNs); !polled.ok() && !reported) {
      std::fprintf(stderr, "flat2dd: gpio.pps: %s (retrying)\n", polled.error().message.c_str());
      reported = true;  // once: a dead line would otherwise fill the journal at 4 Hz
    }
  }
}

Status GpioWiring::PollPps(TimeNs timeout_ns) {
  if (!pps_input_) return Status::Ok();
  const Result<bool> waited = pps_source_->Wait(timeout_ns);  // unlocked: blocks up to the timeout
  const std::lock_guard lock(pps_mutex_);
  if (waited.ok() && !*waited) return Status::Ok();
  // The edges are pending now: this Poll does not wait.
  const Result<hal::gpio::PpsPollResult> polled =
      waited.ok() ? pps_input_->Poll(0) : Result<hal::gpio::PpsPollResult>(waited.error());
  if (!polled.ok()) {
    ++pps_read_errors_;
    return polled.error();
  }
  pps_dropped_events_ += polled->dropped_events;
  return Status::Ok();
}

api::v1::GpioHealth GpioWiring::Health(TimeNs now_realtime_ns) const {
  api::v1::GpioHealth health;
  {
    const std::lock_guard lock(output_mutex_);
    health.set_pose_valid_configured(pose_valid_.has_value());
    if (pose_valid_) {
      health.set_pose_valid_on(pose_valid_->on());
      health.set_pose_valid_switches(pose_valid_->switches());
      health.set_pose_valid_write_failures(pose_valid_->write_failures());
    }
  }
  const std::lock_guard lock(pps_mutex_);
  if (!pps_clock_) return health;
  const hal::gpio::PpsEstimate estimate = pps_clock_->Estimate(now_realtime_ns);
  health.set_pps_state(StateOf(estimate.status));
  if (estimate.valid) {
    health.set_pps_offset_us(static_cast<double>(estimate.offset_ns) * kNsToUs);
    health.set_pps_drift_ppm(estimate.drift_ppm);
    health.set_pps_jitter_us(estimate.jitter_ns * kNsToUs);
  }
  health.set_pps_pulses(estimate.counters.accepted);
  health.set_pps_missed(estimate.counters.missed);
  health.set_pps_spurious(estimate.counters.spurious);
  health.set_pps_dropped_events(pps_dropped_events_);
  health.set_pps_read_errors(pps_read_errors_);
  return health;
}

}  // namespace flat2d::daemon
