// libgpiod v1 backend of the GPIO HAL (gpio_lines.hpp): edge-event inputs and outputs.
//
// Debian 12 ships libgpiod 1.6, the v1 API over the kernel's v1 character-device uAPI.
// Steps: open the chip (by name "gpiochip0", path "/dev/gpiochip0", number "0", or label),
// find the line by offset or by name, request it as consumer "flat2d" (edge events with an
// optional active-low flag, or an output with its initial value), and release it and close
// the chip on destruction. Open failures name the chip and line ("gpiochip0: No such file
// or directory", "line 17 on gpiochip0 is busy (used by 'pps-gpio')").
//
// Timestamps: the v1 uAPI stamps each event in the interrupt handler, with CLOCK_REALTIME
// before Linux 5.7 and CLOCK_MONOTONIC since (kernel commit 26d060e47e25, "gpiolib: use
// monotonic clock for event timestamps"); libgpiod 1.6 passes the stamp through as-is.
// EdgeEvent::time_ns is CLOCK_REALTIME either way: monotonic stamps are shifted by the
// realtime-minus-monotonic offset sampled at each Read. The offset can only move between
// edge and read by what an NTP slew does in that time (< 1 us for a read within 2 ms).
// v1 events carry no kernel sequence numbers: the backend numbers them as it reads them, so
// an overflow of the kernel's 16-event FIFO (a reader asleep for 16 pulses) is invisible.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/gpio/gpio_lines.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace flat2d::hal::gpio {

struct LineAddress {
  // "gpiochip0", "/dev/gpiochip0", "0", or the chip's label (as gpioinfo prints it).
  std::string chip;
  // Offset of the line on the chip; used when `name` is empty.
  unsigned offset = 0;
  // Line name from the device tree or gpio-line-names (gpiod_chip_find_line: the first line
  // of that name on the chip). Overrides `offset` when set.
  std::string name;
};

enum class EdgeSelection : std::uint8_t { kRising, kFalling, kBoth };

struct EdgeInputOptions {
  LineAddress line;
  // A PPS pulse is marked by its rising edge (the GPS receiver's datasheet says which).
  EdgeSelection edges = EdgeSelection::kRising;
  // Inverts the line: the edges then refer to the logical (inverted) level.
  bool active_low = false;
  // Shown by gpioinfo and in "busy" errors of other programs.
  std::string consumer = "flat2d";
};

struct OutputOptions {
  LineAddress line;
  // Driven from the moment of the request, so the line never glitches to the other level.
  bool initial_value = false;
  std::string consumer = "flat2d";
};

// The clock the kernel's v1 uAPI stamps line events with, from a `uname -r` release string
// ("6.1.0-18-amd64"): CLOCK_MONOTONIC from 5.7 on, CLOCK_REALTIME before. An unparsable
// release is taken as a modern kernel.
enum class EventClock : std::uint8_t { kRealtime, kMonotonic };
EventClock V1EventClockForKernel(std::string_view release);

namespace detail {
struct ChipCloser {
  void operator()(gpiod_chip* chip) const;
};
struct LineReleaser {
  void operator()(gpiod_line* line) const;
};
// A requested line and the chip that owns it; the line is released before the chip closes.
struct RequestedLine {
  std::unique_ptr<gpiod_chip, ChipCloser> chip;
  std::unique_ptr<gpiod_line, LineReleaser> line;
  std::string description;  // "line 17 on gpiochip0", for error messages
};
}  // namespace detail

class LibgpiodEdgeInput final : public EdgeEventSource {
 public:
  static Result<LibgpiodEdgeInput> Open(const EdgeInputOptions& options);

  Result<bool> Wait(TimeNs timeout_ns) override;
  Result<std::size_t> Read(std::span<EdgeEvent> out) override;

  const std::string& description() const { return line_.description; }
  EventClock kernel_clock() const { return kernel_clock_; }

 private:
  LibgpiodEdgeInput(detail::RequestedLine line, EventClock kernel_clock);

  detail::RequestedLine line_;
  EventClock kernel_clock_;
  std::uint64_t next_sequence_ = 0;
};

class LibgpiodOutput final : public DigitalOutput {
 public:
  static Result<LibgpiodOutput> Open(const OutputOptions& options);

  Status Set(bool value) override;
  bool value() const override { return value_; }

  const std::string& description() const { return line_.description; }

 private:
  LibgpiodOutput(detail::RequestedLine line, bool value);

  detail::RequestedLine line_;
  bool value_;
};

}  // namespace flat2d::hal::gpio
