// The GPIO lines flat2dd's configuration names (gpio { pose_valid pps }): the pose-valid
// output, driven from the supervisor's tick, and the PPS input, polled by its own thread.
//
// Either, both or neither may be configured; what is not configured does nothing and is
// reported as such. The output is off (its safe value) from the moment it is requested, and
// Stop() latches it off before the daemon's threads stop. The PPS estimate is kept under a
// mutex: the PPS thread feeds it, the API thread reads it for the status; the thread waits
// for edges outside the lock, so a status request never waits for a pulse.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>

#include "daemon/api/flat2d_api.pb.h"
#include "daemon/config/flat2dd_config.pb.h"
#include "hal/common/error.hpp"
#include "hal/gpio/gpio_lines.hpp"
#include "hal/gpio/pose_valid_output.hpp"
#include "hal/gpio/pps_clock.hpp"
#include "hal/gpio/pps_input.hpp"

namespace flat2d::daemon {

// The hal options a validated configuration stands for.
hal::gpio::PoseValidOptions PoseValidOptionsFor(const PoseValidOutputConfig& config);
hal::gpio::PpsClockOptions PpsClockOptionsFor(const PpsInputConfig& config);

class GpioWiring {
 public:
  // Requests the configured lines through libgpiod. Errors name the line ("gpio.pps: line 4
  // on gpiochip0: Device or resource busy").
  static Result<std::unique_ptr<GpioWiring>> Open(const GpioConfig& config);

  // On lines the caller owns (each null when that part is not configured); they must
  // outlive the wiring. For tests and other backends.
  static Result<std::unique_ptr<GpioWiring>> Create(const GpioConfig& config, hal::gpio::DigitalOutput* pose_valid_line,
                                                    hal::gpio::EdgeEventSource* pps_source);

  ~GpioWiring();

  bool has_pps() const { return pps_input_.has_value(); }

  // Supervisor: whether the pose is valid (LOCALIZED) at `now_ns` (CLOCK_MONOTONIC).
  void UpdatePoseValid(bool pose_valid, TimeNs now_ns);
  // Drives the output off for good: the daemon is stopping.
  void Stop();

  // PPS thread: polls edges until stop is requested; a failing line is reported in the
  // status and retried.
  void RunPps(std::stop_token stop);
  // One wait of at most `timeout_ns` for edges, then every pending edge fed to the estimate.
  Status PollPps(TimeNs timeout_ns);
  std::uint64_t pps_heartbeat() const { return pps_heartbeat_.load(std::memory_order_relaxed); }

  // Any thread; `now_realtime_ns` is CLOCK_REALTIME, the clock PPS edges are stamped with.
  api::v1::GpioHealth Health(TimeNs now_realtime_ns) const;

 private:
  struct OwnedLines;
  GpioWiring() = default;

  std::unique_ptr<OwnedLines> owned_;  // libgpiod lines, when opened by Open
  mutable std::mutex output_mutex_;
  std::optional<hal::gpio::PoseValidOutput> pose_valid_;
  hal::gpio::EdgeEventSource* pps_source_ = nullptr;
  mutable std::mutex pps_mutex_;
  std::optional<hal::gpio::PpsClock> pps_clock_;
  std::optional<hal::gpio::PpsInput> pps_input_;
  std::uint64_t pps_dropped_events_ = 0;
  std::uint64_t pps_read_errors_ = 0;
  std::atomic<std::uint64_t> pps_heartbeat_{0};
};

}  // namespace flat2d::daemon
