// Drives the "pose valid" output line from the localization state, without chatter.
//
// The line tells other vehicle systems that flat2d's pose can be trusted, so every rule errs
// towards off:
//  1. An invalid pose turns the line off at once; it is never held on.
//  2. The pose must stay valid for min_on_ms before the line turns on, so a pose that
//     flickers between valid and invalid never turns it on.
//  3. Once turned off, the line stays off for at least min_off_ms, so it turns on at most
//     once per min_off_ms however the pose chatters.
// Off is the safe state: driven when the output is created, when the daemon says it is
// stopping (Stop, latched), and on destruction. The active level maps "on" to the line's
// value, so a consumer that reads a low line as "valid" is served without rewiring.
#pragma once

#include <cstdint>
#include <optional>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/gpio/gpio_lines.hpp"

namespace flat2d::hal::gpio {

enum class ActiveLevel : std::uint8_t { kHigh, kLow };

struct PoseValidOptions {
  // How long the pose must stay valid before the line turns on (>= 0).
  std::int64_t min_on_ms = 500;
  // How long the line stays off once turned off (>= 0).
  std::int64_t min_off_ms = 1000;
  // The line value that means "pose valid".
  ActiveLevel active_level = ActiveLevel::kHigh;
};

// Configuration errors name the field.
Status ValidatePoseValidOptions(const PoseValidOptions& options);

// The line value meaning "not valid": request the output line with it as the initial value,
// so the line is safe from the moment it is requested.
constexpr bool PoseValidSafeValue(const PoseValidOptions& options) {
  return options.active_level == ActiveLevel::kLow;
}

class PoseValidOutput {
 public:
  // Validates the options and drives the line off. `line` must outlive the output.
  static Result<PoseValidOutput> Create(DigitalOutput& line, const PoseValidOptions& options);

  PoseValidOutput(PoseValidOutput&& other) noexcept;
  PoseValidOutput& operator=(PoseValidOutput&&) = delete;
  ~PoseValidOutput();  // drives the line off

  // The localization state at `now_ns`, a steady clock (CLOCK_MONOTONIC). An error is a
  // failed line write; the state is unchanged and the write is retried on the next Update.
  Status Update(bool pose_valid, TimeNs now_ns);

  // Drives the line off and ignores later Updates (the daemon is stopping).
  Status Stop();

  bool on() const { return on_; }
  bool stopped() const { return stopped_; }
  std::uint64_t switches() const { return switches_; }  // off->on and on->off changes
  std::uint64_t write_failures() const { return write_failures_; }

 private:
  PoseValidOutput(DigitalOutput& line, const PoseValidOptions& options)
      : line_(&line), options_(options) {}

  Status Drive(bool on, TimeNs now_ns);

  DigitalOutput* line_;  // null once moved from
  PoseValidOptions options_;
  bool on_ = false;
  bool stopped_ = false;
  std::optional<TimeNs> valid_since_;  // start of the current run of valid poses
  std::optional<TimeNs> off_since_;    // last on->off switch
  std::uint64_t switches_ = 0;
  std::uint64_t write_failures_ = 0;
};

}  // namespace flat2d::hal::gpio
