#include "hal/gpio/pose_valid_output.hpp"

#include <string>
#include <utility>

namespace flat2d::hal::gpio {

Status ValidatePoseValidOptions(const PoseValidOptions& options) {
  if (options.min_on_ms < 0) {
    return MakeError("pose_valid.min_on_ms must be >= 0, got " + std::to_string(options.min_on_ms));
  }
  if (options.min_off_ms < 0) {
    return MakeError("pose_valid.min_off_ms must be >= 0, got " +
                     std::to_string(options.min_off_ms));
  }
  return {};
}

Result<PoseValidOutput> PoseValidOutput::Create(DigitalOutput& line,
                                                const PoseValidOptions& options) {
  if (Status valid = ValidatePoseValidOptions(options); !valid.ok()) return valid.error();
  PoseValidOutput output(line, options);
  if (Status off = output.Drive(false, 0); !off.ok()) return off.error();
  return output;
}

PoseValidOutput::PoseValidOutput(PoseValidOutput&& other) noexcept
    : line_(std::exchange(other.line_, nullptr)),
      options_(other.options_),
      on_(other.on_),
      stopped_(other.stopped_),
      valid_since_(other.valid_since_),
      off_since_(other.off_since_),
      switches_(other.switches_),
      write_failures_(other.write_failures_) {}

PoseValidOutput::~PoseValidOutput() {
  // Best effort: nothing to report to from a destructor, and a retry cannot do better.
  if (line_ != nullptr) (void)line_->Set(PoseValidSafeValue(options_));
}

Status PoseValidOutput::Update(bool pose_valid, TimeNs now_ns) {
  if (stopped_) return {};
  if (!pose_valid) {
    valid_since_.reset();
    return on_ ? Drive(false, now_ns) : Status{};
  }
  if (!valid_since_) valid_since_ = now_ns;
  if (on_) return {};
  const bool held_valid = now_ns - *valid_since_ >= options_.min_on_ms * kNsPerMs;
  const bool rested = !off_since_ || now_ns - *off_since_ >= options_.min_off_ms * kNsPerMs;
  return held_valid && rested ? Drive(true, now_ns) : Status{};
}

Status PoseValidOutput::Stop() {
  stopped_ = true;
  return Drive(false, 0);
}

Status PoseValidOutput::Drive(bool on, TimeNs now_ns) {
  const bool value = on == (options_.active_level == ActiveLevel::kHigh);
  if (Status written = line_->Set(value); !written.ok()) {
    ++write_failures_;
    return written;
  }
  if (on != on_) {
    ++switches_;
    if (!on) off_since_ = now_ns;
  }
  on_ = on;
  return {};
}

}  // namespace flat2d::hal::gpio
